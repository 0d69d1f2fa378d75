#pragma once
// The peer in `bench step --peer bullet` (issue 13): Bullet's soft body (btSoftBody, Debian's libbullet,
// double precision) on the same closed control mesh and the same constraint set as the deformable body:
// one link per hull edge, one per bend (the wing pair across a hinge: Bullet's links are distance
// constraints, as the bends are), one per spoke to a fixed centre node at the core. Same substeps and
// iterations (Bullet's position iterations, piterations), one thread, gravity on, no contact.
#include <deform/body_settings.hpp>

#include <cstddef>
#include <cstdint>

namespace sandbox::baselines {

struct PeerStepCost {
  std::size_t nodes = 0;                   ///< control points + the centre
  std::size_t links = 0;                   ///< edges + bends + spokes
  double us_per_step = 0;                  ///< median thread CPU time of one step (all substeps) [us]
  double ns_per_constraint_iteration = 0;  ///< us_per_step / (links x substeps x iterations)
  bool finite = true;                      ///< every node finite at the end
};

/// Steps the Bullet body `warmup` + `steps` steps of `dt_s`, each `substeps` internal steps of
/// `iterations` position iterations, and times the measured ones.
PeerStepCost bulletPeerStepCost(const deform::BodySettings& settings, double mass_kg, uint32_t substeps,
                                uint32_t iterations, std::size_t warmup, std::size_t steps, double dt_s);

}  // namespace sandbox::baselines

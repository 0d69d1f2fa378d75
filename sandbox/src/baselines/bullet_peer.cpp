#include "baselines/bullet_peer.hpp"

#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <memory>
#include <vector>

namespace sandbox::baselines {
namespace {

double threadCpuUs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e6 * static_cast<double>(t.tv_sec) + 1e-3 * static_cast<double>(t.tv_nsec);
}

}  // namespace

PeerStepCost bulletPeerStepCost(const deform::BodySettings& settings, double mass_kg, uint32_t substeps,
                                uint32_t iterations, std::size_t warmup, std::size_t steps, double dt_s) {
  btSoftBodyRigidBodyCollisionConfiguration config;
  btCollisionDispatcher dispatcher(&config);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btSoftRigidDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
  world.setGravity(btVector3(0, 0, -9.81));
  btSoftBodyWorldInfo& info = world.getWorldInfo();
  info.m_gravity = btVector3(0, 0, -9.81);
  info.m_sparsesdf.Initialize();

  const std::size_t n = settings.rest_positions_m.size();
  std::vector<btVector3> positions;
  std::vector<btScalar> masses;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d& p = settings.rest_positions_m[i];
    positions.emplace_back(p.x(), p.y(), p.z());
    masses.push_back(settings.mass_kg[i]);
  }
  const Eigen::Vector3d& c = settings.core_m;
  positions.emplace_back(c.x(), c.y(), c.z());
  masses.push_back(0);  // Bullet: zero mass is a fixed node, as our core is kinematic
  auto body = std::make_unique<btSoftBody>(&info, static_cast<int>(positions.size()), positions.data(),
                                           masses.data());
  const int centre = static_cast<int>(n);
  for (const auto& e : settings.edges) body->appendLink(static_cast<int>(e.a), static_cast<int>(e.b));
  for (const auto& b : settings.bends) body->appendLink(static_cast<int>(b.left), static_cast<int>(b.right));
  for (const auto& s : settings.spokes) body->appendLink(static_cast<int>(s.point), centre);
  for (const auto& t : settings.triangles)
    body->appendFace(static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2]));
  body->m_materials[0]->m_kLST = 0.9;
  body->m_cfg.piterations = static_cast<int>(iterations);
  (void)mass_kg;  // the masses are the control points' own (their sum is the shell's share of mass_kg)
  world.addSoftBody(body.get());

  PeerStepCost cost;
  cost.nodes = static_cast<std::size_t>(body->m_nodes.size());
  cost.links = static_cast<std::size_t>(body->m_links.size());
  const btScalar substep_s = dt_s / substeps;
  std::vector<double> us;
  for (std::size_t k = 0; k < warmup + steps; ++k) {
    const double start = threadCpuUs();
    for (uint32_t s = 0; s < substeps; ++s) world.stepSimulation(substep_s, 0);  // exactly one step
    if (k >= warmup) us.push_back(threadCpuUs() - start);
  }
  std::nth_element(us.begin(), us.begin() + static_cast<std::ptrdiff_t>(us.size() / 2), us.end());
  cost.us_per_step = us.empty() ? 0 : us[us.size() / 2];
  cost.ns_per_constraint_iteration =
      1e3 * cost.us_per_step / static_cast<double>(cost.links * substeps * iterations);
  for (int i = 0; i < body->m_nodes.size(); ++i) {
    const btVector3& x = body->m_nodes[i].m_x;
    cost.finite = cost.finite && std::isfinite(x.x()) && std::isfinite(x.y()) && std::isfinite(x.z());
  }
  world.removeSoftBody(body.get());
  return cost;
}

}  // namespace sandbox::baselines

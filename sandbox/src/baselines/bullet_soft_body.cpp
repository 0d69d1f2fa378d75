#include "baselines/bullet_soft_body.hpp"

#include "elapsed.hpp"

#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <unordered_set>
#include <vector>

namespace sandbox::baselines {
namespace {

// A soft-rigid world with a ground plane at z = 0; owns what it creates.
struct BulletWorld {
  btSoftBodyRigidBodyCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btSoftRigidDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btDefaultMotionState>> motion_states;
  std::vector<std::unique_ptr<btRigidBody>> rigid_bodies;
  std::unique_ptr<btSoftBody> soft;

  BulletWorld() {
    world.setGravity(btVector3(0, 0, -9.81));
    btSoftBodyWorldInfo& info = world.getWorldInfo();
    info.m_gravity = btVector3(0, 0, -9.81);
    info.m_sparsesdf.Initialize();
    addStatic(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0), btVector3(0, 0, 0));
  }
  ~BulletWorld() {
    if (soft) world.removeSoftBody(soft.get());
    for (auto& body : rigid_bodies) world.removeRigidBody(body.get());
  }
  BulletWorld(const BulletWorld&) = delete;
  BulletWorld& operator=(const BulletWorld&) = delete;

  void addStatic(std::unique_ptr<btCollisionShape> shape, const btVector3& origin) {
    btTransform pose;
    pose.setIdentity();
    pose.setOrigin(origin);
    motion_states.push_back(std::make_unique<btDefaultMotionState>(pose));
    btRigidBody::btRigidBodyConstructionInfo info(0, motion_states.back().get(), shape.get());
    info.m_friction = 0.6;
    rigid_bodies.push_back(std::make_unique<btRigidBody>(info));
    world.addRigidBody(rigid_bodies.back().get());
    shapes.push_back(std::move(shape));
  }

  // One node per vertex lifted by `lift_m`, one link per edge (built here: btSoftBodyHelpers::
  // CreateFromTriMesh allocates an n x n table), the triangles as faces.
  btSoftBody& addSoftBody(const deform::Mesh& mesh, double mass_kg, double lift_m) {
    std::vector<btVector3> positions;
    positions.reserve(mesh.positions_m.size());
    for (const auto& p : mesh.positions_m) positions.emplace_back(p.x(), p.y(), p.z() + lift_m);
    std::vector<btScalar> masses(positions.size(), 1.0);
    soft = std::make_unique<btSoftBody>(&world.getWorldInfo(), static_cast<int>(positions.size()),
                                        positions.data(), masses.data());
    std::unordered_set<uint64_t> edges;
    for (const auto& t : mesh.triangles) {
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = std::min(t[k], t[(k + 1) % 3]), b = std::max(t[k], t[(k + 1) % 3]);
        if (edges.insert(uint64_t{a} << 32 | b).second)
          soft->appendLink(static_cast<int>(a), static_cast<int>(b));
      }
      soft->appendFace(static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2]));
    }
    soft->m_materials[0]->m_kLST = 0.9;
    soft->m_cfg.piterations = 4;
    soft->m_cfg.kDF = 0.5;
    soft->m_cfg.kVC = 20;
    soft->m_cfg.kMT = 0.05;
    soft->setTotalMass(mass_kg, false);
    soft->setPose(true, true);
    world.addSoftBody(soft.get());
    return *soft;
  }
};

bool allFinite(const btSoftBody& body) {
  for (int i = 0; i < body.m_nodes.size(); ++i) {
    const btVector3& x = body.m_nodes[i].m_x;
    if (!std::isfinite(x.x()) || !std::isfinite(x.y()) || !std::isfinite(x.z())) return false;
  }
  return true;
}

double diagonal(const btSoftBody& body) {
  btVector3 lo(1e300, 1e300, 1e300), hi(-1e300, -1e300, -1e300);
  for (int i = 0; i < body.m_nodes.size(); ++i) {
    lo.setMin(body.m_nodes[i].m_x);
    hi.setMax(body.m_nodes[i].m_x);
  }
  return (hi - lo).length();
}

btVector3 centroid(const btSoftBody& body) {
  btVector3 sum(0, 0, 0);
  for (int i = 0; i < body.m_nodes.size(); ++i) sum += body.m_nodes[i].m_x;
  return sum / static_cast<btScalar>(std::max(body.m_nodes.size(), 1));
}

}  // namespace

SoftBodyCost bulletSoftBodyCost(const deform::Mesh& mesh, double mass_kg, int frames, int substeps) {
  SoftBodyCost cost;
  const deform::Aabb box = deform::boundingBox(mesh);
  const auto start = Clock::now();
  BulletWorld bullet;
  btSoftBody& body = bullet.addSoftBody(mesh, mass_kg, 0.02 - box.min_m.z());
  cost.build_ms = msSince(start);
  cost.nodes = static_cast<std::size_t>(body.m_nodes.size());
  cost.links = static_cast<std::size_t>(body.m_links.size());
  cost.faces = static_cast<std::size_t>(body.m_faces.size());
  std::vector<double> ms;
  const btScalar frame_s = 1.0 / 60.0;
  for (int f = 0; f < frames; ++f) {
    const auto t0 = Clock::now();
    bullet.world.stepSimulation(frame_s, substeps, frame_s / substeps);
    ms.push_back(msSince(t0));
  }
  std::nth_element(ms.begin(), ms.begin() + static_cast<std::ptrdiff_t>(ms.size() / 2), ms.end());
  cost.ms_per_frame = ms.empty() ? 0 : ms[ms.size() / 2];
  cost.finite = allFinite(body);
  return cost;
}

SoftBodyCrash bulletWallCrash(const deform::Mesh& mesh, double mass_kg, double speed_kmh, double duration_s,
                              double physics_hz) {
  SoftBodyCrash crash;
  crash.speed_kmh = speed_kmh;
  const deform::Aabb box = deform::boundingBox(mesh);
  BulletWorld bullet;
  const double near_face_m = box.max_m.x() + 1.0, thickness_m = 0.2;
  bullet.addStatic(std::make_unique<btBoxShape>(btVector3(thickness_m / 2, 2.0, 1.0)),
                   btVector3(near_face_m + thickness_m / 2, 0, 1.0));
  btSoftBody& body = bullet.addSoftBody(mesh, mass_kg, 0.02 - box.min_m.z());
  const double speed_mps = speed_kmh / 3.6;
  body.setVelocity(btVector3(speed_mps, 0, 0));
  const double rest_diagonal = diagonal(body);
  std::vector<btVector3> rest(static_cast<std::size_t>(body.m_nodes.size()));
  for (int i = 0; i < body.m_nodes.size(); ++i) rest[static_cast<std::size_t>(i)] = body.m_nodes[i].m_x;
  const btVector3 rest_centroid = centroid(body);

  const auto steps = static_cast<long>(std::llround(duration_s * physics_hz));
  const btScalar dt = 1.0 / physics_hz;
  for (long k = 0; k < steps && crash.finite; ++k) {
    bullet.world.stepSimulation(dt, 0);  // one step of exactly dt
    crash.finite = allFinite(body);
    if (!crash.finite) break;
    for (int i = 0; i < body.m_nodes.size(); ++i) {
      crash.tunnelled = crash.tunnelled || body.m_nodes[i].m_x.x() > near_face_m + thickness_m;
      crash.max_node_speed_mps = std::max(crash.max_node_speed_mps, double(body.m_nodes[i].m_v.length()));
    }
    crash.max_extent_growth = std::max(crash.max_extent_growth, diagonal(body) / rest_diagonal - 1.0);
  }
  if (crash.finite) {
    const btVector3 moved = centroid(body) - rest_centroid;
    for (int i = 0; i < body.m_nodes.size(); ++i) {
      const double d = (body.m_nodes[i].m_x - moved - rest[static_cast<std::size_t>(i)]).length();
      crash.residual_dent_m = std::max(crash.residual_dent_m, d);
    }
  }
  crash.stable = crash.finite && !crash.tunnelled && crash.max_extent_growth < 1.0 &&
                 crash.max_node_speed_mps < 10 * std::max(speed_mps, 1.0);
  char text[200];
  if (!crash.finite) {
    std::snprintf(text, sizeof text, "diverged (non-finite nodes)");
  } else {
    std::snprintf(
        text, sizeof text, "%s: extent +%.0f %%, fastest node %.1f m/s, %s, largest node offset %.2f m",
        crash.stable ? "stable" : "unstable", 100 * crash.max_extent_growth, crash.max_node_speed_mps,
        crash.tunnelled ? "TUNNELLED" : "stopped at the wall", crash.residual_dent_m);
  }
  crash.verdict = text;
  return crash;
}

}  // namespace sandbox::baselines

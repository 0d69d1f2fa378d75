#pragma once
// Private ODE helpers of the vehicle library (ODE stays out of the public headers).
#include <vehicle/pose.hpp>

#include <ode/ode.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <type_traits>
#include <vector>

static_assert(std::is_same_v<dReal, double>, "vehicle needs ODE built in double precision (dDOUBLE)");

namespace vehicle::ode {

inline Eigen::Vector3d vec(const dReal* v) {
  return {v[0], v[1], v[2]};
}

/// ODE quaternions are (w, x, y, z).
inline Eigen::Quaterniond quat(const dReal* q) {
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
}
inline std::array<dReal, 4> toOde(const Eigen::Quaterniond& q) {
  return {q.w(), q.x(), q.y(), q.z()};
}

inline Pose bodyPose(dBodyID body) {
  return {vec(dBodyGetPosition(body)), quat(dBodyGetQuaternion(body))};
}
inline Pose geomPose(dGeomID geom) {
  dQuaternion q;
  dGeomGetQuaternion(geom, q);
  return {vec(dGeomGetPosition(geom)), quat(q)};
}
inline void setGeomPose(dGeomID geom, const Pose& pose) {
  dGeomSetPosition(geom, pose.position_m.x(), pose.position_m.y(), pose.position_m.z());
  const auto q = toOde(pose.orientation);
  dGeomSetQuaternion(geom, q.data());
}
inline void setBodyPose(dBodyID body, const Pose& pose) {
  dBodySetPosition(body, pose.position_m.x(), pose.position_m.y(), pose.position_m.z());
  const auto q = toOde(pose.orientation);
  dBodySetQuaternion(body, q.data());
}
inline Eigen::Vector3d pointVelocity(dBodyID body, const Eigen::Vector3d& p) {
  if (body == nullptr) return Eigen::Vector3d::Zero();
  dVector3 v;
  dBodyGetPointVel(body, p.x(), p.y(), p.z(), v);
  return vec(v);
}

/// The arrays an ODE convex geom points into (ODE does not copy them: they must outlive the geom and
/// must not move).
struct ConvexData {
  std::vector<dReal> planes;       ///< a, b, c, d per face: a x + b y + c z = d, outward
  std::vector<dReal> points;       ///< x, y, z per vertex
  std::vector<unsigned> polygons;  ///< per face: vertex count, then the indices (counter-clockwise)
  unsigned face_count = 0;
  unsigned point_count = 0;
};

/// Convex data of a closed outward-wound triangle surface, in the geom's frame (the origin must be
/// inside). Degenerate triangles are left out.
ConvexData makeConvexData(const std::vector<Eigen::Vector3d>& points,
                          const std::vector<std::array<uint32_t, 3>>& triangles);

/// The closest hit of a ray (origin, unit direction, length) with the geoms of `space`, skipping geoms of
/// body `ignore` (the car's own chassis).
struct RayHit {
  bool hit = false;
  double distance_m = 0;
  Eigen::Vector3d point_m{0, 0, 0};
  Eigen::Vector3d normal{0, 0, 1};  ///< facing back along the ray
  dBodyID body = nullptr;           ///< the body hit, or null for a static geom
};
RayHit castRay(dSpaceID space, dGeomID ray, const Eigen::Vector3d& origin_m, const Eigen::Vector3d& direction,
               double length_m, dBodyID ignore);

/// Which entity a geom belongs to, packed into its user-data pointer: (kind + 1) << 32 | index.
inline void* packEntity(uint32_t kind, uint32_t index) {
  return reinterpret_cast<void*>(static_cast<std::uintptr_t>((uint64_t{kind} + 1) << 32 | index));
}
inline bool unpackEntity(const void* data, uint32_t& kind, uint32_t& index) {
  const auto code = static_cast<uint64_t>(reinterpret_cast<std::uintptr_t>(data));
  if ((code >> 32) == 0) return false;
  kind = static_cast<uint32_t>((code >> 32) - 1);
  index = static_cast<uint32_t>(code & 0xffffffffu);
  return true;
}

}  // namespace vehicle::ode

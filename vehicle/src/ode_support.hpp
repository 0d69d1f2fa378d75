#pragma once
// Private ODE helpers of the vehicle library (ODE stays out of the public headers).
#include <vehicle/pose.hpp>
#include <vehicle/state_io.hpp>

#include "geom_grid.hpp"

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
/// Keeps the body's orientation at a quaternion ODE's normalisation leaves unchanged (ode_state.cpp):
/// ODE normalises every quaternion it is given (dBodySetQuaternion), and the one its step leaves is not
/// always a fixed point of that, so a saved orientation could not be put back bit for bit. The nearest
/// fixed point (a few units in the last place away) is taken instead, after every step and at creation.
void keepOrientationRestorable(dBodyID body);

inline void setBodyPose(dBodyID body, const Pose& pose) {
  dBodySetPosition(body, pose.position_m.x(), pose.position_m.y(), pose.position_m.z());
  const auto q = toOde(pose.orientation);
  dBodySetQuaternion(body, q.data());
  keepOrientationRestorable(body);
}

/// A body's motion state (position, quaternion, linear and angular velocity, enabled) to and from saved
/// bytes, bit for bit. restoreBody throws deform::InputError (through `in`) when the saved quaternion is
/// not one ODE keeps unchanged (a state not written by saveBody).
void saveBody(StateWriter& out, dBodyID body);
void restoreBody(StateReader& in, dBodyID body, const char* what);

/// The order of `space`'s geoms (it decides the order collision pairs, hence contacts, are found in) as
/// indices into `known` (every geom in the space, in a fixed order), and back: restoreGeomOrder makes
/// every geom dirty in the saved order (what a step leaves: the moved geoms in front). Throws through
/// `in` for an order that is not a permutation of `known`.
/// With `moving_only` (for a hash) only geoms on a body are listed: static geoms never move, so after the
/// first step they follow every moving one in the order they were made.
void saveGeomOrder(StateWriter& out, dSpaceID space, const std::vector<dGeomID>& known,
                   bool moving_only = false);
void restoreGeomOrder(StateReader& in, dSpaceID space, const std::vector<dGeomID>& known);
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

/// The closest hit of a ray (origin, unit direction, length) with the geoms of the space `geoms` was built
/// from, skipping geoms of body `ignore` (the car's own chassis); `scratch` holds the candidates.
struct RayHit {
  bool hit = false;
  double distance_m = 0;
  Eigen::Vector3d point_m{0, 0, 0};
  Eigen::Vector3d normal{0, 0, 1};  ///< facing back along the ray
  dBodyID body = nullptr;           ///< the body hit, or null for a static geom
};
/// The nearest hit along the ray of a geom whose face there turns at least `min_facing` (the cosine of
/// the angle between its normal and the ray, reversed) back towards the ray's origin; steeper faces are
/// looked past.
RayHit castRay(const GeomGrid& geoms, dGeomID ray, const Eigen::Vector3d& origin_m,
               const Eigen::Vector3d& direction, double length_m, dBodyID ignore, std::vector<int>& scratch,
               double min_facing = -1.0);

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

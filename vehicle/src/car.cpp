// The car: chassis body and convex hull, and the wheel forces of each step (ray, suspension, tyre),
// applied with dBodyAddForceAtPos as Kenwright 2015 and Bullet's btRaycastVehicle drive their cars.
#include <vehicle/car.hpp>
#include <vehicle/mass_properties.hpp>

#include "ode_support.hpp"

#include <deform/error.hpp>
#include <vehicle/state_io.hpp>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

namespace vehicle {

struct Car::ConvexGeom {
  ode::ConvexData data;
  dGeomID geom = nullptr;
};

namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;
// The steepest face a wheel stands on: within 60 degrees of its suspension axis (the cosine). A steeper
// face is no road for the tyre (its hull meets it): the ray looks past it. A wheel's ray that met the
// side of another car's hull (its normal 87 degrees off) compressed the suspension to 2 cm of its
// 0.62 m and pushed the two cars into each other with 570 kN (random campaign seed 8, scene 55: 62 kJ
// created).
const double kSteepestSupport = std::cos(std::numbers::pi / 3);

/// Wheel loads of a level car at rest: the smallest-norm loads that balance weight, roll and pitch
/// (sum F_i = W, sum F_i x_i = 0, sum F_i y_i = 0 with x, y from the centre of mass), the usual axle
/// split for a symmetric four-wheel layout [N].
std::vector<double> staticLoads(const std::vector<Eigen::Vector2d>& contact_xy_m, double weight_N) {
  const std::size_t n = contact_xy_m.size();
  std::vector<double> loads(n, weight_N / static_cast<double>(n));
  Eigen::MatrixXd a(3, static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<Eigen::Index>(i);
    a(0, c) = 1;
    a(1, c) = contact_xy_m[i].x();
    a(2, c) = contact_xy_m[i].y();
  }
  const Eigen::Matrix3d normal = a * a.transpose();
  if (std::abs(normal.determinant()) < 1e-9) return loads;
  const Eigen::VectorXd f = a.transpose() * normal.ldlt().solve(Eigen::Vector3d(weight_N, 0, 0));
  for (std::size_t i = 0; i < n; ++i)
    loads[i] = std::max(f[static_cast<Eigen::Index>(i)], 0.05 * weight_N / static_cast<double>(n));
  return loads;
}

}  // namespace

Car::Car(dxWorld* world, dxSpace* space, void* geom_data, const deform::ControlMesh& hull,
         const VehicleSettings& settings, std::vector<WheelSettings> wheels, const Pose& vehicle_pose,
         const Eigen::Vector3d& velocity_mps)
    : settings_(settings), wheel_settings_(std::move(wheels)), hull_(hull), space_(space) {
  // Mass and inertia: the solid hull at uniform density (consistent with deform's tetrahedral mass split;
  // a real car is denser low down, which centre_of_mass_offset_m can express).
  const SolidProperties solid = solidProperties(hull.points_m, hull.triangles, "vehicle hull");
  centre_of_mass_m_ = solid.centroid_m + settings.centre_of_mass_offset_m;
  inertia_kg_m2_ = shiftedInertia(settings.mass_kg * solid.inertia_per_kg, settings.mass_kg,
                                  settings.centre_of_mass_offset_m);

  body_ = dBodyCreate(world);
  setChassisMass(settings.mass_kg, inertia_kg_m2_);

  convex_ = std::make_unique<ConvexGeom>();
  setCollisionHull(hull);
  dGeomSetData(convex_->geom, geom_data);
  ray_ = dCreateRay(nullptr, 1.0);

  // Suspension mounts: above each hub by the spring length left at its static load, so the car settles
  // level with its wheels at their design centres.
  std::vector<Eigen::Vector2d> contacts;
  for (const auto& w : wheel_settings_) contacts.emplace_back((w.centre_m - centre_of_mass_m_).head<2>());
  const std::vector<double> loads = staticLoads(contacts, settings.mass_kg * kGravity_mps2);
  wheels_.resize(wheel_settings_.size());
  const double forward_speed = velocity_mps.dot(vehicle_pose.orientation * Eigen::Vector3d::UnitX());
  double front_x = 0, rear_x = 0, left_y = -1e300, right_y = 1e300;
  int fronts = 0, rears = 0;
  for (std::size_t i = 0; i < wheel_settings_.size(); ++i) {
    const WheelSettings& w = wheel_settings_[i];
    const double compression = std::min(loads[i] / w.spring_N_per_m, 0.9 * w.suspension_length_m);
    mount_body_m_.push_back(w.centre_m - centre_of_mass_m_ +
                            Eigen::Vector3d(0, 0, w.suspension_length_m - compression));
    wheels_[i].compression_m = compression;
    wheels_[i].normal_load_N = loads[i];
    wheels_[i].tyre.spin_rad_s = forward_speed / w.radius_m;
    if (w.steered) {
      front_x += w.centre_m.x();
      ++fronts;
      left_y = std::max(left_y, w.centre_m.y());
      right_y = std::min(right_y, w.centre_m.y());
    } else {
      rear_x += w.centre_m.x();
      ++rears;
    }
  }
  wheelbase_m_ = fronts > 0 && rears > 0 ? front_x / fronts - rear_x / rears : 0.0;
  track_m_ = fronts > 1 ? left_y - right_y : 0.0;

  ode::setBodyPose(body_, {vehicle_pose.toWorld(centre_of_mass_m_), vehicle_pose.orientation});
  dBodySetLinearVel(body_, velocity_mps.x(), velocity_mps.y(), velocity_mps.z());
}

Car::~Car() {
  if (ray_) dGeomDestroy(ray_);
  if (convex_ && convex_->geom) dGeomDestroy(convex_->geom);
  clearCore();
  if (body_) dBodyDestroy(body_);
}

void Car::setInput(const DriverInput& input) {
  input_ = input;
  input_.throttle = std::isfinite(input.throttle) ? std::clamp(input.throttle, 0.0, 1.0) : 0.0;
  input_.brake = std::isfinite(input.brake) ? std::clamp(input.brake, 0.0, 1.0) : 0.0;
  input_.steering = std::isfinite(input.steering) ? std::clamp(input.steering, -1.0, 1.0) : 0.0;
  if (input.steer_angle_rad && !std::isfinite(*input.steer_angle_rad)) input_.steer_angle_rad.reset();
}

Pose Car::bodyPose() const {
  return ode::bodyPose(body_);
}

Pose Car::vehiclePose() const {
  const Pose body = bodyPose();
  return {body.position_m - body.orientation * centre_of_mass_m_, body.orientation};
}

Eigen::Vector3d Car::velocity_mps() const {
  return ode::vec(dBodyGetLinearVel(body_));
}
Eigen::Vector3d Car::angularVelocity_rad_s() const {
  return ode::vec(dBodyGetAngularVel(body_));
}
double Car::forwardSpeed_mps() const {
  return velocity_mps().dot(bodyPose().orientation * Eigen::Vector3d::UnitX());
}

Pose Car::wheelPose(std::size_t i) const {
  const Pose body = bodyPose();
  const WheelSettings& w = wheel_settings_[i];
  const WheelState& s = wheels_[i];
  const Eigen::Vector3d down = body.orientation * Eigen::Vector3d(0, 0, -1);
  const Eigen::Vector3d hub =
      body.toWorld(mount_body_m_[i]) + (w.suspension_length_m - s.compression_m) * down;
  const Eigen::Quaterniond turn = body.orientation *
                                  Eigen::AngleAxisd(s.steer_angle_rad, Eigen::Vector3d::UnitZ()) *
                                  Eigen::AngleAxisd(s.rotation_rad, Eigen::Vector3d::UnitY());
  return {hub, turn};
}

void Car::setChassisMass(double mass_kg, const Eigen::Matrix3d& inertia_kg_m2) {
  chassis_mass_kg_ = mass_kg;
  chassis_inertia_kg_m2_ = inertia_kg_m2;
  dMass mass;
  dMassSetZero(&mass);
  mass.mass = mass_kg;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) mass.I[4 * r + c] = inertia_kg_m2(r, c);
  dBodySetMass(body_, &mass);
}

void Car::carryShell(double shell_mass_kg, const Eigen::Matrix3d& shell_inertia_kg_m2) {
  const double rest_kg = settings_.mass_kg - shell_mass_kg;
  const Eigen::Matrix3d rest_inertia = inertia_kg_m2_ - shell_inertia_kg_m2;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> principal(0.5 *
                                                                 (rest_inertia + rest_inertia.transpose()));
  if (!(shell_mass_kg >= 0) || !(rest_kg > 0.01 * settings_.mass_kg) ||
      !(principal.eigenvalues().minCoeff() > 0.01 * inertia_kg_m2_.trace() / 3))
    throw deform::InputError(
        "vehicle.deformation.shell_mass_fraction: the shell's points would carry nearly all of the car's " +
        std::string(rest_kg > 0.01 * settings_.mass_kg ? "inertia (they lie on its surface)" : "mass") +
        ", leaving the chassis none; lower the fraction");
  setChassisMass(rest_kg, rest_inertia);
}

void Car::setCollisionHull(const deform::ControlMesh& hull) {
  std::vector<Eigen::Vector3d> local;
  local.reserve(hull.points_m.size());
  for (const auto& p : hull.points_m) local.push_back(p - centre_of_mass_m_);
  ode::ConvexData fresh = ode::makeConvexData(local, hull.triangles);
  if (convex_->geom == nullptr) {
    convex_->geom = dCreateConvex(space_, fresh.planes.data(), fresh.face_count, fresh.points.data(),
                                  fresh.point_count, fresh.polygons.data());
    dGeomSetBody(convex_->geom, body_);
  } else {
    dGeomSetConvex(convex_->geom, fresh.planes.data(), fresh.face_count, fresh.points.data(),
                   fresh.point_count, fresh.polygons.data());
  }
  convex_->data = std::move(fresh);  // moving keeps the buffers ODE points into
  hull_ = hull;
}

void Car::clearCore() {
  for (auto& core : core_)
    if (core->geom) dGeomDestroy(core->geom);
  core_.clear();
}

void Car::setCoreHull(double allowance_m, void* geom_data) {
  clearCore();
  if (!(allowance_m > 0)) return;
  // Each point moved the stroke horizontally towards the centre of mass (at most to a tenth of its
  // distance); heights kept, so the core is as tall as the car and a wall cannot lift it over itself.
  std::vector<Eigen::Vector3d> inner;
  for (const auto& p : hull_.points_m) {
    const Eigen::Vector3d r = p - centre_of_mass_m_;
    const double length = std::hypot(r.x(), r.y());
    const double keep = length > 0 ? std::max(0.1, 1.0 - allowance_m / length) : 1.0;
    inner.emplace_back(r.x() * keep, r.y() * keep, r.z());
  }
  addCoreGeom(inner, geom_data);
}

void Car::setCoreBoxes(const std::vector<deform::Aabb>& boxes_m, void* geom_data) {
  clearCore();
  // ODE boxes at an offset from the centre of mass (a convex geom must hold its body's origin, and an
  // engine block does not).
  for (const deform::Aabb& box : boxes_m) {
    const Eigen::Vector3d size = box.size_m();
    const Eigen::Vector3d centre = 0.5 * (box.min_m + box.max_m) - centre_of_mass_m_;
    auto geom = std::make_unique<ConvexGeom>();
    geom->geom =
        dCreateBox(space_, std::max(size.x(), 1e-3), std::max(size.y(), 1e-3), std::max(size.z(), 1e-3));
    dGeomSetBody(geom->geom, body_);
    dGeomSetOffsetPosition(geom->geom, centre.x(), centre.y(), centre.z());
    dGeomSetData(geom->geom, geom_data);
    core_.push_back(std::move(geom));
  }
}

void Car::addCoreGeom(const std::vector<Eigen::Vector3d>& points_body_m, void* geom_data) {
  const deform::ControlMesh core = deform::convexHull(points_body_m, "crush backstop");
  auto geom = std::make_unique<ConvexGeom>();
  geom->data = ode::makeConvexData(core.points_m, core.triangles);
  geom->geom = dCreateConvex(space_, geom->data.planes.data(), geom->data.face_count,
                             geom->data.points.data(), geom->data.point_count, geom->data.polygons.data());
  dGeomSetBody(geom->geom, body_);
  dGeomSetData(geom->geom, geom_data);
  core_.push_back(std::move(geom));
}

ObstacleShape Car::shape() const {
  ObstacleShape out;
  out.type = ShapeType::Convex;
  const Pose pose = vehiclePose();
  out.centre_m.setZero();
  for (const auto& p : hull_.points_m) {
    out.vertices_m.push_back(pose.toWorld(p));
    out.centre_m += out.vertices_m.back();
  }
  if (!out.vertices_m.empty()) out.centre_m /= static_cast<double>(out.vertices_m.size());
  return out;
}

void Car::applyForces(double dt_s, const ode::GeomGrid& geoms) {
  const Pose body = bodyPose();
  const Eigen::Matrix3d rotation = body.orientation.toRotationMatrix();
  const Eigen::Vector3d down = -rotation.col(2);

  // Steering: the driver's target, rate-limited, then split over the front wheels.
  const double max_steer = settings_.max_steer_rad;
  const double target = input_.steer_angle_rad ? std::clamp(*input_.steer_angle_rad, -max_steer, max_steer)
                                               : input_.steering * max_steer;
  steer_rad_ = rateLimited(steer_rad_, target, settings_.steer_rate_rad_s, dt_s);
  const auto steer = ackermannAngles(steer_rad_, wheelbase_m_, track_m_, settings_.ackermann);

  // Engine: peak torque through the fixed gear, capped by power at the driven wheels' mean speed.
  int driven = 0;
  double driven_spin = 0;
  for (std::size_t i = 0; i < wheels_.size(); ++i) {
    if (!wheel_settings_[i].driven) continue;
    ++driven;
    driven_spin += std::abs(wheels_[i].tyre.spin_rad_s);
  }
  double wheel_torque_Nm = 0;
  if (driven > 0 && input_.throttle > 0) {
    const double spin = driven_spin / driven;
    const double torque = std::min(settings_.engine_torque_Nm * settings_.gear_ratio,
                                   settings_.max_power_W / std::max(spin, 1e-3));
    wheel_torque_Nm = (input_.reverse ? -1.0 : 1.0) * input_.throttle * torque / driven;
  }

  for (std::size_t i = 0; i < wheels_.size(); ++i) {
    const WheelSettings& w = wheel_settings_[i];
    WheelState& s = wheels_[i];
    s.steer_angle_rad = w.steered ? (w.centre_m.y() >= centre_of_mass_m_.y() ? steer[0] : steer[1]) : 0.0;

    TyreStepInput in;
    in.dt_s = dt_s;
    in.radius_m = w.radius_m;
    in.inertia_kg_m2 = w.inertia_kg_m2;
    in.drive_torque_Nm = w.driven ? wheel_torque_Nm : 0.0;
    in.brake_torque_Nm = input_.brake * w.brake_torque_Nm +
                         (input_.handbrake && w.handbrake ? settings_.handbrake_torque_Nm : 0.0);

    const double reach = w.suspension_length_m + w.radius_m;
    const ode::RayHit hit = ode::castRay(geoms, ray_, body.toWorld(mount_body_m_[i]), down, reach, body_,
                                         ray_candidates_, kSteepestSupport);
    Eigen::Vector3d forward = Eigen::Vector3d::Zero(), left = Eigen::Vector3d::Zero();
    s.in_contact = hit.hit;
    if (hit.hit) {
      const Eigen::Vector3d n = hit.normal;
      const Eigen::Vector3d relative =
          ode::pointVelocity(body_, hit.point_m) - ode::pointVelocity(hit.body, hit.point_m);
      const double incidence = -n.dot(down);  // cosine between the suspension axis and the normal
      s.compression_m = reach - hit.distance_m;
      const double rate = incidence > 0.1 ? -relative.dot(n) / incidence : 0.0;
      s.normal_load_N = suspensionForce(s.compression_m, rate, w);
      const Eigen::Vector3d heading =
          rotation * Eigen::Vector3d(std::cos(s.steer_angle_rad), std::sin(s.steer_angle_rad), 0);
      forward = heading - heading.dot(n) * n;
      if (forward.norm() < 1e-6) forward = rotation.col(0) - rotation.col(0).dot(n) * n;
      forward.normalize();
      left = n.cross(forward);
      in.normal_load_N = s.normal_load_N;
      in.longitudinal_speed_mps = relative.dot(forward);
      in.lateral_speed_mps = relative.dot(left);
      s.contact_point_m = hit.point_m;
      s.contact_normal = n;
    } else {
      s.compression_m = 0;
      s.normal_load_N = 0;
    }
    const TyreStepResult tyre = stepTyre(s.tyre, in, settings_.tyre);
    s.drive_torque_Nm = in.drive_torque_Nm;
    s.sliding = tyre.force.sliding;
    s.locked = tyre.locked;
    s.slip_ratio = tyre.slip_ratio;
    s.slip_angle_rad = tyre.slip_angle_rad;
    s.rotation_rad = std::fmod(s.rotation_rad + s.tyre.spin_rad_s * dt_s, kTwoPi);
    if (s.rotation_rad < 0) s.rotation_rad += kTwoPi;
    s.force_N.setZero();
    if (hit.hit) {
      s.force_N = s.normal_load_N * s.contact_normal + tyre.force.longitudinal_N * forward +
                  tyre.force.lateral_N * left;
      const Eigen::Vector3d& p = s.contact_point_m;
      dBodyAddForceAtPos(body_, s.force_N.x(), s.force_N.y(), s.force_N.z(), p.x(), p.y(), p.z());
      if (hit.body != nullptr) {  // what the tyre stands on is pushed back (another car, a fallen tree)
        dBodyEnable(hit.body);
        dBodyAddForceAtPos(hit.body, -s.force_N.x(), -s.force_N.y(), -s.force_N.z(), p.x(), p.y(), p.z());
      }
    }
  }

  // Aerodynamic drag at the centre of mass: -1/2 rho C_d A |v| v.
  const Eigen::Vector3d v = velocity_mps();
  const Eigen::Vector3d drag = -0.5 * settings_.air_density_kg_m3 * settings_.drag_area_m2 * v.norm() * v;
  dBodyAddForce(body_, drag.x(), drag.y(), drag.z());
}

namespace {

void saveMesh(StateWriter& out, const deform::ControlMesh& mesh) {
  out.u64(mesh.points_m.size());
  for (const auto& p : mesh.points_m) out.vec(p);
  out.u64(mesh.triangles.size());
  for (const auto& t : mesh.triangles) out.raw(t.data(), sizeof t);
  out.u64(mesh.edges.size());
  for (const auto& e : mesh.edges) out.raw(&e, sizeof e);
  out.vec(mesh.centre_of_mass_m);
  out.real(mesh.volume_m3);
  out.u64(mesh.hull_vertex_count);
  out.u64(mesh.mirror_of.size());
  out.raw(mesh.mirror_of.data(), mesh.mirror_of.size() * sizeof(uint32_t));
}

deform::ControlMesh restoreMesh(StateReader& in) {
  deform::ControlMesh mesh;
  mesh.points_m.resize(in.count(24));
  for (auto& p : mesh.points_m) p = in.vec();
  mesh.triangles.resize(in.count(12));
  for (auto& t : mesh.triangles) {
    in.raw(t.data(), sizeof t);
    for (uint32_t i : t) in.expect(i < mesh.points_m.size(), "collision hull: a corner out of range");
  }
  mesh.edges.resize(in.count(sizeof(deform::ControlEdge)));
  for (auto& e : mesh.edges) in.raw(&e, sizeof e);
  mesh.centre_of_mass_m = in.vec();
  mesh.volume_m3 = in.real();
  mesh.hull_vertex_count = static_cast<std::size_t>(in.u64());
  mesh.mirror_of.resize(in.count(4));
  in.raw(mesh.mirror_of.data(), mesh.mirror_of.size() * sizeof(uint32_t));
  return mesh;
}

bool sameSurface(const deform::ControlMesh& a, const deform::ControlMesh& b) {
  return a.points_m.size() == b.points_m.size() && a.triangles == b.triangles &&
         std::memcmp(a.points_m.data(), b.points_m.data(), a.points_m.size() * sizeof(Eigen::Vector3d)) == 0;
}

}  // namespace

void Car::saveState(StateWriter& out) const {
  ode::saveBody(out, body_);
  out.real(steer_rad_);
  out.real(input_.throttle);
  out.real(input_.brake);
  out.real(input_.steering);
  out.flag(input_.steer_angle_rad.has_value());
  out.real(input_.steer_angle_rad.value_or(0.0));
  out.flag(input_.handbrake);
  out.flag(input_.reverse);
  out.u64(wheels_.size());
  for (const WheelState& s : wheels_) {
    for (double x :
         {s.steer_angle_rad, s.rotation_rad, s.tyre.spin_rad_s, s.tyre.longitudinal_deflection_m,
          s.tyre.lateral_deflection_m, s.compression_m, s.normal_load_N, s.slip_ratio, s.slip_angle_rad})
      out.real(x);
    for (bool b : {s.in_contact, s.sliding, s.locked}) out.flag(b);
    out.vec(s.contact_point_m);
    out.vec(s.contact_normal);
    out.vec(s.force_N);
  }
  saveMesh(out, hull_);
}

void Car::restoreState(StateReader& in) {
  ode::restoreBody(in, body_, "car chassis");
  steer_rad_ = in.real();
  input_.throttle = in.real();
  input_.brake = in.real();
  input_.steering = in.real();
  const bool has_angle = in.flag();
  const double angle = in.real();
  input_.steer_angle_rad = has_angle ? std::optional<double>(angle) : std::nullopt;
  input_.handbrake = in.flag();
  input_.reverse = in.flag();
  in.expect(in.u64() == wheels_.size(), "wheel count does not match the car");
  for (WheelState& s : wheels_) {
    for (double* x :
         {&s.steer_angle_rad, &s.rotation_rad, &s.tyre.spin_rad_s, &s.tyre.longitudinal_deflection_m,
          &s.tyre.lateral_deflection_m, &s.compression_m, &s.normal_load_N, &s.slip_ratio, &s.slip_angle_rad})
      *x = in.real();
    for (bool* b : {&s.in_contact, &s.sliding, &s.locked}) *b = in.flag();
    s.contact_point_m = in.vec();
    s.contact_normal = in.vec();
    s.force_N = in.vec();
  }
  deform::ControlMesh hull = restoreMesh(in);
  in.expect(hull.points_m.size() >= 4 && hull.triangles.size() >= 4, "collision hull: too few points");
  if (!sameSurface(hull, hull_)) setCollisionHull(hull);  // re-hulled since the start
  hull_ = std::move(hull);
}

void Car::appendGeoms(std::vector<dxGeom*>& out) const {
  out.push_back(convex_->geom);
  for (const auto& core : core_) out.push_back(core->geom);
}

}  // namespace vehicle

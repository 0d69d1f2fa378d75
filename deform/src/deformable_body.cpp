// The XPBD step of a deformable body (Macklin, Mueller, Chentanez 2016, Algorithm 1, with the
// substepping of Macklin et al. 2019, "Small Steps in Physics Simulation", Algorithm 1).
#include <deform/deformable_body.hpp>
#include <deform/error.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace deform {
namespace {

void checkSizes(const BodySettings& settings, const BodyState& state) {
  if (state.positions_m.size() != settings.pointCount() ||
      state.velocities_mps.size() != settings.pointCount() ||
      state.edge_rest_m.size() != settings.edges.size() ||
      state.spoke_rest_m.size() != settings.spokes.size() ||
      state.bend_rest_m.size() != settings.bends.size())
    throw InputError("body state: sizes do not match the body settings");
}

}  // namespace

DeformableBody::DeformableBody(std::shared_ptr<const BodySettings> settings, const SolverParams& params)
    : settings_(std::move(settings)), params_(params) {
  if (!settings_) throw InputError("body settings: missing");
  checkSolverParams(params_);
  state_ = restState(*settings_);
  previous_m_.resize(settings_->pointCount());
  edge_lambda_.resize(settings_->edges.size());
  spoke_lambda_.resize(settings_->spokes.size());
  bend_lambda_.resize(settings_->bends.size());
  for (double r : settings_->spoke_rest_m) radius_m_ = std::max(radius_m_, r);
}

void DeformableBody::setState(BodyState state) {
  checkSizes(*settings_, state);
  state_ = std::move(state);
}

void DeformableBody::setParams(const SolverParams& params) {
  checkSolverParams(params);
  params_ = params;
}

bool DeformableBody::loadChanged() const {
  // Bound on the change of the inertial acceleration at the furthest control point (radius R):
  // |d(g - a_c)| + |d alpha| R + |d omega| (|omega_0| + |omega_1|) R, scaled.
  const BodyState& s = state_;
  const double change = (load_mps2_ - s.sleep_load_mps2).norm() +
                        (alpha_radps2_ - s.sleep_angular_acceleration_radps2).norm() * radius_m_ +
                        (omega_radps_ - s.sleep_angular_velocity_radps).norm() *
                            (omega_radps_.norm() + s.sleep_angular_velocity_radps.norm()) * radius_m_;
  return params_.inertial_scale * change > params_.wake_load_mps2;
}

StepReport DeformableBody::step(const StepInputs& inputs, double dt_s) {
  if (!std::isfinite(dt_s) || dt_s <= 0)
    throw InputError("dt_s: time step must be finite and > 0 (got " + std::to_string(dt_s) + " s)");
  const BodySettings& settings = *settings_;
  for (std::size_t k = 0; k < inputs.impulses.size(); ++k) {
    const PointImpulse& impulse = inputs.impulses[k];
    const std::string field = "impulses[" + std::to_string(k) + "]";
    if (impulse.point >= settings.pointCount()) throw InputError(field + ".point: no such control point");
    if (!impulse.impulse_Ns.allFinite()) throw InputError(field + ".impulse_Ns: not finite");
  }
  for (std::size_t k = 0; k < inputs.contacts.size(); ++k)
    checkContactShape(inputs.contacts[k], ("contacts[" + std::to_string(k) + "]").c_str());
  if (!std::isfinite(inputs.contact_friction) || inputs.contact_friction < 0)
    throw InputError("contact_friction: must be finite and >= 0 (got " +
                     std::to_string(inputs.contact_friction) + ")");
  const ChassisMotion& chassis = inputs.chassis;
  if (!chassis.acceleration_mps2.allFinite() || !chassis.angular_velocity_radps.allFinite() ||
      !chassis.angular_acceleration_radps2.allFinite() || !chassis.gravity_mps2.allFinite())
    throw InputError("chassis: motion not finite");
  load_mps2_ = chassis.gravity_mps2 - chassis.acceleration_mps2;
  omega_radps_ = chassis.angular_velocity_radps;
  alpha_radps2_ = chassis.angular_acceleration_radps2;

  StepReport report;
  bool load_changed = false;
  if (state_.sleeping) {
    load_changed = loadChanged();
    if (inputs.contacts.empty() && inputs.impulses.empty() && !load_changed) {
      report.asleep = true;
      state_.time_s += dt_s;
      return report;
    }
    state_.sleeping = false;
    if (load_changed || !inputs.impulses.empty()) state_.sleep_timer_s = 0;
  }

  for (const PointImpulse& impulse : inputs.impulses)
    state_.velocities_mps[impulse.point] += impulse.impulse_Ns * settings.inverse_mass_per_kg[impulse.point];

  const double h = dt_s / static_cast<double>(params_.substeps);
  for (uint32_t k = 0; k < params_.substeps; ++k) substep(h, inputs, report);
  state_.time_s += dt_s;

  // Sleep bookkeeping.
  double max_speed2 = 0;
  for (const Eigen::Vector3d& v : state_.velocities_mps) max_speed2 = std::max(max_speed2, v.squaredNorm());
  report.max_speed_mps = std::sqrt(max_speed2);
  const bool quiet =
      report.contact_points == 0 && inputs.impulses.empty() && report.max_speed_mps < params_.sleep_speed_mps;
  state_.sleep_timer_s = quiet ? state_.sleep_timer_s + dt_s : 0.0;
  if (quiet && params_.sleep_delay_s >= 0 && state_.sleep_timer_s >= params_.sleep_delay_s) {
    state_.sleeping = true;
    for (Eigen::Vector3d& v : state_.velocities_mps) v.setZero();
    state_.sleep_load_mps2 = load_mps2_;
    state_.sleep_angular_velocity_radps = omega_radps_;
    state_.sleep_angular_acceleration_radps2 = alpha_radps2_;
  }
  return report;
}

uint32_t DeformableBody::findContacts(const StepInputs& inputs) {
  // Points inside an obstacle or within the margin of it: a point resting on a surface at the start of
  // the substep stays held by its (inactive until violated) contact instead of sinking in for a substep
  // and being thrown out the next, a jitter.
  contacts_.clear();
  face_contacts_.clear();
  const auto& x = state_.positions_m;
  Penetration p;
  uint32_t inside = 0;
  for (std::size_t k = 0; k < inputs.contacts.size(); ++k) {
    const ContactShape& shape = inputs.contacts[k];
    const bool surface = k < inputs.surface_contact.size() && inputs.surface_contact[k];
    if (surface) touched_.assign(x.size(), 0);
    for (uint32_t i = 0; i < x.size(); ++i)
      if (penetration(shape, x[i], p, params_.contact_margin_m)) {
        contacts_.push_back({i, p.normal, x[i] + p.depth_m * p.normal});
        inside += p.depth_m > 0;
        if (surface && p.depth_m > 0) touched_[i] = 1;
      }
    if (surface) inside += findFaceContacts(shape);
  }
  return inside;
}

uint32_t DeformableBody::findFaceContacts(const ContactShape& shape) {
  // A thin obstacle (a bollard, another car's corner) can come through the control surface between its
  // points, where no point is inside it. Points on each triangle, a grid at most kFaceSampleSpacing_m
  // apart, are queried like the control points; one found inside pushes the triangle's corners out along
  // the obstacle's normal, weighted by its barycentric coordinates. Not next to a control point the
  // obstacle already holds: that point makes the dent (a pole's narrow notch).
  constexpr double kFaceSampleSpacing_m = 0.1;
  constexpr int kMostSamplesPerEdge = 8;
  Eigen::Vector3d centre;
  double radius = 0;
  if (!boundingSphere(shape, centre, radius)) return 0;  // a half-space meets the points first
  const BodySettings& settings = *settings_;
  const auto& x = state_.positions_m;
  uint32_t found = 0;
  Penetration p;
  for (const auto& t : settings.triangles) {
    if (touched_[t[0]] || touched_[t[1]] || touched_[t[2]]) continue;
    const Eigen::Vector3d& a = x[t[0]];
    const Eigen::Vector3d& b = x[t[1]];
    const Eigen::Vector3d& c = x[t[2]];
    const Eigen::Vector3d g = (a + b + c) / 3.0;
    const double reach =
        std::sqrt(std::max({(a - g).squaredNorm(), (b - g).squaredNorm(), (c - g).squaredNorm()}));
    if ((g - centre).norm() > radius + reach) continue;  // broad phase: the spheres do not meet
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const int k =
        std::clamp(static_cast<int>(std::ceil(longest / kFaceSampleSpacing_m)), 2, kMostSamplesPerEdge);
    for (int i = 0; i <= k; ++i) {
      for (int j = 0; i + j <= k; ++j) {
        if (i == k || j == k || i + j == 0) continue;  // the corners are control points themselves
        const Eigen::Vector3d bary(static_cast<double>(i) / k, static_cast<double>(j) / k,
                                   static_cast<double>(k - i - j) / k);
        const Eigen::Vector3d q = bary[0] * a + bary[1] * b + bary[2] * c;
        if (!penetration(shape, q, p, 0.0) || !(p.depth_m > 0)) continue;
        face_contacts_.push_back({t, bary, p.normal, q + p.depth_m * p.normal});
        ++found;
      }
    }
  }
  return found;
}

void DeformableBody::substep(double h, const StepInputs& inputs, StepReport& report) {
  const BodySettings& settings = *settings_;
  const std::size_t n = settings.pointCount();
  auto& x = state_.positions_m;
  auto& v = state_.velocities_mps;
  const auto& w = settings.inverse_mass_per_kg;
  const Eigen::Vector3d core = settings.core_m;

  // Prediction: exact viscous decay, explicit velocity update with the inertial forces, then positions.
  const double scale = params_.inertial_scale;
  const double decay = std::exp(-params_.damping_per_s * h);
  const bool inertial = scale > 0 && (load_mps2_.squaredNorm() > 0 || omega_radps_.squaredNorm() > 0 ||
                                      alpha_radps2_.squaredNorm() > 0);
  for (std::size_t i = 0; i < n; ++i) {
    previous_m_[i] = x[i];
    // Drag first, then the load: at rest (v = 0) the full load acts, so damping leaves the static
    // equilibrium where the compliance alone puts it.
    Eigen::Vector3d vi = v[i] * decay;
    if (inertial) {
      const Eigen::Vector3d r = x[i] - core;
      const Eigen::Vector3d a = load_mps2_ - alpha_radps2_.cross(r) -
                                omega_radps_.cross(omega_radps_.cross(r)) - 2.0 * omega_radps_.cross(vi);
      vi += (h * scale) * a;
    }
    Eigen::Vector3d travel = h * vi;
    // Numeric guard: a point can end a substep at most 2 d_max from where it began (visual constraint),
    // so a larger predicted travel (an enormous impulse) is shortened to that before the solve.
    const double cap = 2.0 * settings.max_deviation_m[i];
    const double travel2 = travel.squaredNorm();
    if (travel2 > cap * cap) travel *= cap / std::sqrt(travel2);
    x[i] += travel;
  }

  report.contact_points += findContacts(inputs);

  // Gauss-Seidel sweeps, each constraint kind in its own loop; multipliers start at zero each substep.
  std::fill(edge_lambda_.begin(), edge_lambda_.end(), 0.0);
  std::fill(spoke_lambda_.begin(), spoke_lambda_.end(), 0.0);
  std::fill(bend_lambda_.begin(), bend_lambda_.end(), 0.0);
  const double inv_h2 = 1.0 / (h * h);
  const std::size_t edge_count = settings.edges.size(), spoke_count = settings.spokes.size(),
                    bend_count = settings.bends.size();
  const EdgeConstraint* edges = settings.edges.data();
  const SpokeConstraint* spokes = settings.spokes.data();
  const BendConstraint* bends = settings.bends.data();
  const double* edge_rest = state_.edge_rest_m.data();
  const double* spoke_rest = state_.spoke_rest_m.data();
  const double* bend_rest = state_.bend_rest_m.data();
  for (uint32_t it = 0; it < params_.iterations; ++it) {
    for (std::size_t k = 0; k < edge_count; ++k) {
      const EdgeConstraint& c = edges[k];
      projectDistance(x[c.a], x[c.b], w[c.a], w[c.b], edge_rest[k], c.compliance_m_per_N * inv_h2,
                      edge_lambda_[k]);
    }
    for (std::size_t k = 0; k < spoke_count; ++k) {
      const SpokeConstraint& c = spokes[k];
      projectSpoke(x[c.point], core, w[c.point], spoke_rest[k], c.compliance_m_per_N * inv_h2,
                   spoke_lambda_[k]);
    }
    for (std::size_t k = 0; k < bend_count; ++k) {
      const BendConstraint& c = bends[k];
      projectDistance(x[c.left], x[c.right], w[c.left], w[c.right], bend_rest[k],
                      c.compliance_m_per_N * inv_h2, bend_lambda_[k]);
    }
    for (const ContactPoint& c : contacts_)
      projectContact(x[c.point], previous_m_[c.point], c.normal, c.surface_m, inputs.contact_friction);
    for (const FaceContact& c : face_contacts_) {
      const auto& k = c.corners;
      const double inverse_mass[3] = {w[k[0]], w[k[1]], k[2] == k[0] ? 0.0 : w[k[2]]};
      projectFaceContact(x[k[0]], x[k[1]], x[k[2]], inverse_mass, c.bary, c.normal, c.surface_m);
    }
  }

  // The shell stays bolted to the chassis: no rotation of the whole shell about the core.
  removeShellRotation(x.data(), settings.rest_positions_m.data(), settings.mass_kg.data(), n, core,
                      settings.shell_inverse_inertia);

  // Visual constraint, the last projection of the substep (Kenwright 2015, "Visual Constraints").
  for (std::size_t i = 0; i < n; ++i)
    projectVisual(x[i], settings.rest_positions_m[i], settings.max_deviation_m[i]);

  plasticity(report);

  // Velocities from positions (Verlet style; XPBD Algorithm 1, line 16).
  const double inv_h = 1.0 / h;
  for (std::size_t i = 0; i < n; ++i) v[i] = (x[i] - previous_m_[i]) * inv_h;
}

void DeformableBody::plasticity(StepReport& report) {
  const BodySettings& settings = *settings_;
  const auto& x = state_.positions_m;
  const auto& laws = settings.plastic_laws;
  double work_J = 0;
  // One constraint: new rest length by the return map; the plastic work is the force that remains after
  // the flow (the yield force, |l - L'| / alpha) times the flow |dL| (the 1D sigma_y d eps_p). A rigid
  // constraint (alpha = 0) stores no elastic energy and has no defined yield force: its flow is counted
  // at zero work.
  auto flow = [&](double length, double& rest, double original, uint32_t material, double compliance) {
    const double moved = plasticRestLength(length, rest, original, laws[material]);
    if (moved == rest) return;
    if (compliance > 0) work_J += std::abs(length - moved) / compliance * std::abs(moved - rest);
    rest = moved;
  };
  for (std::size_t k = 0; k < settings.edges.size(); ++k) {
    const EdgeConstraint& c = settings.edges[k];
    flow((x[c.a] - x[c.b]).norm(), state_.edge_rest_m[k], settings.edge_rest_m[k], c.material,
         c.compliance_m_per_N);
  }
  for (std::size_t k = 0; k < settings.spokes.size(); ++k) {
    const SpokeConstraint& c = settings.spokes[k];
    flow((x[c.point] - settings.core_m).norm(), state_.spoke_rest_m[k], settings.spoke_rest_m[k], c.material,
         c.compliance_m_per_N);
  }
  for (std::size_t k = 0; k < settings.bends.size(); ++k) {
    const BendConstraint& c = settings.bends[k];
    flow((x[c.left] - x[c.right]).norm(), state_.bend_rest_m[k], settings.bend_rest_m[k], c.material,
         c.compliance_m_per_N);
  }
  state_.plastic_work_J += work_J;
  report.plastic_work_J += work_J;
}

BodyEnergy bodyEnergy(const BodySettings& settings, const BodyState& state) {
  BodyEnergy e;
  const auto& x = state.positions_m;
  for (std::size_t i = 0; i < x.size(); ++i)
    e.kinetic_J += 0.5 * settings.mass_kg[i] * state.velocities_mps[i].squaredNorm();
  auto elastic = [&e](double c, double compliance) {
    if (compliance > 0) e.elastic_J += 0.5 * c * c / compliance;
  };
  for (std::size_t k = 0; k < settings.edges.size(); ++k) {
    const auto& c = settings.edges[k];
    elastic((x[c.a] - x[c.b]).norm() - state.edge_rest_m[k], c.compliance_m_per_N);
  }
  for (std::size_t k = 0; k < settings.spokes.size(); ++k) {
    const auto& c = settings.spokes[k];
    elastic((x[c.point] - settings.core_m).norm() - state.spoke_rest_m[k], c.compliance_m_per_N);
  }
  for (std::size_t k = 0; k < settings.bends.size(); ++k) {
    const auto& c = settings.bends[k];
    elastic((x[c.left] - x[c.right]).norm() - state.bend_rest_m[k], c.compliance_m_per_N);
  }
  return e;
}

double maxDeviation(const BodySettings& settings, const BodyState& state) {
  double worst2 = 0;
  for (std::size_t i = 0; i < state.positions_m.size(); ++i)
    worst2 = std::max(worst2, (state.positions_m[i] - settings.rest_positions_m[i]).squaredNorm());
  return std::sqrt(worst2);
}

double constraintStrainRms(const BodySettings& settings, const BodyState& state) {
  double sum2 = 0;
  std::size_t count = 0;
  const auto add = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, double rest_m) {
    if (!(rest_m > 0)) return;
    const double strain = ((a - b).norm() - rest_m) / rest_m;
    sum2 += strain * strain;
    ++count;
  };
  const auto& x = state.positions_m;
  for (std::size_t k = 0; k < settings.edges.size(); ++k)
    add(x[settings.edges[k].a], x[settings.edges[k].b], state.edge_rest_m[k]);
  for (std::size_t k = 0; k < settings.spokes.size(); ++k)
    add(x[settings.spokes[k].point], settings.core_m, state.spoke_rest_m[k]);
  for (std::size_t k = 0; k < settings.bends.size(); ++k)
    add(x[settings.bends[k].left], x[settings.bends[k].right], state.bend_rest_m[k]);
  return count > 0 ? std::sqrt(sum2 / static_cast<double>(count)) : 0.0;
}

}  // namespace deform

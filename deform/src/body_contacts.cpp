// DeformableBody's contacts: the obstacles placed along their path through the step, the points and
// faces inside them, and the kinetic energy the corrections took.
#include <deform/contact_shapes.hpp>
#include <deform/deformable_body.hpp>

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <variant>

#include "body_halves.hpp"

namespace deform {
namespace {

/// For a point inside `shape` at `end_m` that was at `start_m` when the substep began (relative to the
/// obstacle): `p` becomes the contact at the face it came in through, or, if it was inside already, at the
/// face nearest it then.
void enteredAt(const ContactShape& shape, const Eigen::Vector3d& start_m, const Eigen::Vector3d& end_m,
               Penetration& p) {
  // A point that came in through a face this substep goes back out through it, not through whichever
  // face is nearest now: in a thin wall met faster than half its thickness per substep the nearest face
  // is the far one, and the point would pass through. The entry is found by bisection of the point's
  // path relative to the obstacle (start outside, end inside); `p` becomes the contact at that face.
  constexpr int kBisections = 12;  // the entry to 1/4096 of the substep's travel
  Penetration probe;
  if (penetration(shape, start_m, probe) && probe.depth_m > 0) {
    // Inside already (a correction after the contacts left it a little in): out through the face that
    // was nearest when the substep began.
    const double depth_m = probe.normal.dot(start_m + probe.depth_m * probe.normal - end_m);
    if (depth_m > 0) {
      p.normal = probe.normal;
      p.depth_m = depth_m;
    }
    return;
  }
  Eigen::Vector3d outside = start_m, inside = end_m;
  bisectSurface(shape, outside, inside, kBisections);
  if (!penetration(shape, inside, probe) || !(probe.depth_m > 0)) return;
  // The plane of the entry face, and the end point's depth below it.
  const Eigen::Vector3d surface_m = inside + probe.depth_m * probe.normal;
  const double depth_m = probe.normal.dot(surface_m - end_m);
  if (!(depth_m > 0)) return;
  p.normal = probe.normal;
  p.depth_m = depth_m;
}

/// How deep below the plane through `surface_m` (unit `normal`, out of the obstacle) a point that began
/// the substep at `start_m` may still be when it ends [m]: what it began inside by, less what
/// `max_depenetration_mps` pushes out in `h`; 0 for a point that began outside. Motion further in than
/// where it began is still stopped in full.
double lingeringDepth(const Eigen::Vector3d& normal, const Eigen::Vector3d& surface_m,
                      const Eigen::Vector3d& start_m, double max_depenetration_mps, double h) {
  const double began_inside_m = normal.dot(surface_m - start_m);
  return std::max(0.0, began_inside_m - max_depenetration_mps * h);
}

}  // namespace

Eigen::Vector3d DeformableBody::ShiftedSupport::support(const void* user, const Eigen::Vector3d& direction) {
  const auto& self = *static_cast<const ShiftedSupport*>(user);
  return self.shape.support(self.shape.user, direction) + self.offset_m;
}

void DeformableBody::placeObstacles(const StepInputs& inputs, double behind_s) {
  const std::size_t count = inputs.contacts.size();
  placed_.assign(inputs.contacts.begin(), inputs.contacts.end());
  shifted_.resize(count);  // never reallocated while placed_ points into it: sized before use
  for (std::size_t k = 0; k < count; ++k) {
    Eigen::Vector3d offset{0, 0, 0};
    if (k < inputs.contact_velocity_mps.size()) offset = -behind_s * inputs.contact_velocity_mps[k];
    if (k < obstacle_inverse_mass_.size() && obstacle_inverse_mass_[k] > 0) offset += obstacle_offset_m_[k];
    if (offset.squaredNorm() == 0) continue;
    std::visit(
        [&](auto& shape) {
          using T = std::decay_t<decltype(shape)>;
          if constexpr (std::is_same_v<T, HalfSpaceShape>) {
            shape.offset_m += shape.normal.dot(offset);
          } else if constexpr (std::is_same_v<T, CapsuleShape> || std::is_same_v<T, CylinderShape>) {
            shape.a_m += offset;
            shape.b_m += offset;
          } else if constexpr (std::is_same_v<T, ConvexSupportShape>) {
            shifted_[k] = {shape, offset};
            shape.support = &ShiftedSupport::support;
            shape.user = &shifted_[k];
            shape.centre_m += offset;
            shape.box_min_m += offset;  // an unknown box (infinite corners) stays unknown
            shape.box_max_m += offset;
          } else {
            shape.centre_m += offset;
          }
        },
        placed_[k]);
  }
}

uint32_t DeformableBody::findContacts(const std::vector<ContactShape>& shapes, const StepInputs& inputs,
                                      double h) {
  // Points inside an obstacle or within the margin of it: a point resting on a surface at the start of
  // the substep stays held by its (inactive until violated) contact instead of sinking in for a substep
  // and being thrown out the next, a jitter.
  contacts_.clear();
  face_contacts_.clear();
  const auto& x = state_.positions_m;
  uint32_t inside = 0;
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    const ContactShape& shape = shapes[k];
    const bool surface = k < inputs.surface_contact.size() && inputs.surface_contact[k];
    // The points in two halves (SolverParams::threads), each into its own list, the lists then joined half
    // 0 first: the contacts in point order, as one pass over all points gives them.
    uint32_t inside_of_half[2] = {0, 0};
    const SurelyApart apart(shape, params_.contact_margin_m);
    forEachHalf(params_.threads, [&](int half) {
      std::vector<ContactPoint>& found = contacts_of_half_[half];
      found.clear();
      uint32_t found_inside = 0;
      Penetration p;
      const auto [begin, end] = halfOf(x.size(), half);
      std::vector<uint32_t>& near = near_shape_of_half_[half];
      near.clear();
      apart.listNear(x.data(), begin, end, params_.wide_sweep, near);
      for (const uint32_t i : near)
        if (penetration(shape, x[i], p, params_.contact_margin_m)) {
          // Only a point that moved further than its depth relative to the obstacle this substep can have
          // come in by another face than the nearest (the entry face is at most that travel away).
          const Eigen::Vector3d start_m =
              previous_m_[i] + h * obstacleVelocity(inputs, static_cast<uint32_t>(k), previous_m_[i]);
          if (p.depth_m > 0 && (x[i] - start_m).squaredNorm() > p.depth_m * p.depth_m)
            enteredAt(shape, start_m, x[i], p);
          const Eigen::Vector3d surface_m = x[i] + p.depth_m * p.normal;
          const double lingering_m =
              lingeringDepth(p.normal, surface_m, start_m, params_.max_depenetration_mps, h);
          found.push_back(
              {static_cast<uint32_t>(k), i, p.normal, surface_m - lingering_m * p.normal, start_m});
          found_inside += p.depth_m > 0;
        }
      inside_of_half[half] = found_inside;
    });
    for (int half : {0, 1}) {
      contacts_.insert(contacts_.end(), contacts_of_half_[half].begin(), contacts_of_half_[half].end());
      inside += inside_of_half[half];
    }
    if (surface) inside += findFaceContacts(shape, static_cast<uint32_t>(k), inputs, h);
  }
  return inside;
}

uint32_t DeformableBody::findFaceContacts(const ContactShape& shape, uint32_t shape_index,
                                          const StepInputs& inputs, double h) {
  // A thin obstacle (a bollard, another car's corner) can come through the control surface between its
  // points, where no point is inside it. Points on each triangle, a grid at most kFaceSampleSpacing_m
  // apart, are queried like the control points (with the same margin); one found inside pushes the triangle's
  // corners out along the obstacle's normal, weighted by its barycentric coordinates. Every triangle, also
  // one whose corner the obstacle holds already: skipping those let the surface beside a held point sink into
  // the obstacle unseen, to be thrown out when the point came free (a box's front edge, 30 kJ from nowhere).
  constexpr double kFaceSampleSpacing_m = 0.1;
  constexpr int kMostSamplesPerEdge = 8;
  Eigen::Vector3d centre;
  double radius = 0;
  if (!boundingSphere(shape, centre, radius)) return 0;  // a half-space meets the points first
  const BodySettings& settings = *settings_;
  const auto& x = state_.positions_m;
  uint32_t found = 0;
  Penetration p;
  const bool lipschitz = distanceIsLipschitz(shape);
  // A face point found inside may linger as a control point does (lingeringDepth): where it began the
  // substep, carried with the obstacle, is its corners' start blended.
  auto push = [&](const std::array<uint32_t, 3>& t, const Eigen::Vector3d& bary,
                  const Eigen::Vector3d& normal, const Eigen::Vector3d& surface_m) {
    const Eigen::Vector3d began_m =
        bary[0] * previous_m_[t[0]] + bary[1] * previous_m_[t[1]] + bary[2] * previous_m_[t[2]];
    const Eigen::Vector3d start_m = began_m + h * obstacleVelocity(inputs, shape_index, began_m);
    const double lingering_m = lingeringDepth(normal, surface_m, start_m, params_.max_depenetration_mps, h);
    face_contacts_.push_back({shape_index, t, bary, normal, surface_m - lingering_m * normal});
  };
  for (const auto& t : settings.triangles) {
    const Eigen::Vector3d& a = x[t[0]];
    const Eigen::Vector3d& b = x[t[1]];
    const Eigen::Vector3d& c = x[t[2]];
    const Eigen::Vector3d g = (a + b + c) / 3.0;
    const double reach =
        std::sqrt(std::max({(a - g).squaredNorm(), (b - g).squaredNorm(), (c - g).squaredNorm()}));
    if ((g - centre).norm() > radius + reach) continue;  // broad phase: the spheres do not meet
    // A support shape's box (another car's): the face's box, grown by the margin, outside it meets nothing.
    if (const auto* convex = std::get_if<ConvexSupportShape>(&shape);
        convex &&
        outsideBox(*convex, a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c), params_.contact_margin_m))
      continue;
    // Where the distance is cheap (the primitives), the face's own: no point of it is within the margin
    // when its centroid is further than its reach and the margin (a post's bounding sphere, 2 m into the
    // ground, holds half the car).
    if (!std::holds_alternative<ConvexSupportShape>(shape) &&
        !penetration(shape, g, p, reach + params_.contact_margin_m))
      continue;
    // The centroid's distance outside the obstacle, where the shape's reported distance is a true one
    // (changes by at most a point's move, distanceIsLipschitz): a sample further from the centroid than that
    // distance less the margin is surely not within it, and needs no test (the same contacts: 1e-9 m to
    // spare).
    const double centroid_gap_m =
        lipschitz && p.depth_m < 0 ? -p.depth_m - params_.contact_margin_m - 1e-9 : 0;
    // The obstacle's point deepest into the body across this face (its support point along the inward
    // normal): when it lies behind the face and over it, the obstacle has poked through between the
    // corners, however thin it is (a post narrower than the sample spacing is still met). The samples
    // below still run: for a broad obstacle the support point is a corner, at the edge of its push.
    const Eigen::Vector3d outward = (b - a).cross(c - a);
    const double twice_area = outward.norm();
    // The face is pushed back along its own normal; by a post that pushes across its axis only, along that
    // normal's part across the axis, and not at all by a face it meets within 30 degrees of square (a low
    // stub under the sloping front: pushed along the face's normal, the front rode up it as up a ramp, and
    // a sedan at 200 km/h left a 0.3 m stub 7.7 m up).
    Eigen::Vector3d push_normal{0, 0, 0};
    if (twice_area > 0) {
      push_normal = -outward / twice_area;
      if (const auto* post = std::get_if<CylinderShape>(&shape); post && post->across_only)
        if (!acrossAxis(push_normal, (post->b_m - post->a_m).normalized(), push_normal))
          push_normal.setZero();
    }
    if (push_normal.squaredNorm() > 0) {
      const Eigen::Vector3d normal = outward / twice_area;
      Eigen::Vector3d deepest;
      if (supportPoint(shape, -normal, deepest) && normal.dot(deepest - a) < 0) {
        const Eigen::Vector3d q = deepest - normal.dot(deepest - a) * normal;  // over it, on the face
        const double wa = (b - q).cross(c - q).dot(normal) / twice_area;
        const double wb = (c - q).cross(a - q).dot(normal) / twice_area;
        const double wc = 1.0 - wa - wb;
        if (wa >= 0 && wb >= 0 && wc >= 0 && penetration(shape, q, p, 0.0) && p.depth_m > 0) {
          // The face goes in by the intrusion, but never further than the obstacle's own push-out from
          // that spot: a broad obstacle (another car) has its support point far behind the face.
          const double intrusion_m = std::min(-normal.dot(deepest - a), p.depth_m);
          const Eigen::Vector3d bary(wa, wb, wc);
          const Eigen::Vector3d surface_m = q - intrusion_m * normal;
          push(t, bary, push_normal, surface_m);
          ++found;
        }
      }
    }
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const int k =
        std::clamp(static_cast<int>(std::ceil(longest / kFaceSampleSpacing_m)), 2, kMostSamplesPerEdge);
    for (int i = 0; i <= k; ++i) {
      for (int j = 0; i + j <= k; ++j) {
        if (i == k || j == k || i + j == 0) continue;  // the corners are control points themselves
        const Eigen::Vector3d bary(static_cast<double>(i) / k, static_cast<double>(j) / k,
                                   static_cast<double>(k - i - j) / k);
        const Eigen::Vector3d q = bary[0] * a + bary[1] * b + bary[2] * c;
        if (centroid_gap_m > 0 && (q - g).squaredNorm() < centroid_gap_m * centroid_gap_m) continue;
        // Within the contact margin, as the control points: a sample just outside gets a contact that acts
        // only once violated, so the corrections of this substep cannot leave it inside unseen, to be
        // thrown out at the next one with the speed of its depth (a pole at 2000 points: -5.8 kJ of
        // contact loss, energy from nowhere, of which -6.3 kJ by samples inside at the substep's start).
        if (!penetration(shape, q, p, params_.contact_margin_m)) continue;
        const Eigen::Vector3d surface_m = q + p.depth_m * p.normal;
        push(t, bary, p.normal, surface_m);
        found += p.depth_m > 0;
      }
    }
  }
  return found;
}

Eigen::Vector3d DeformableBody::obstacleVelocity(const StepInputs& inputs, uint32_t shape,
                                                 const Eigen::Vector3d& p_m) const {
  Eigen::Vector3d velocity_mps{0, 0, 0};
  if (shape < inputs.contact_velocity_mps.size()) velocity_mps = inputs.contact_velocity_mps[shape];
  if (shape < inputs.contact_angular_velocity_radps.size())
    velocity_mps += inputs.contact_angular_velocity_radps[shape].cross(p_m - settings_->core_m);
  if (shape < obstacle_inverse_mass_.size() && obstacle_inverse_mass_[shape] > 0)
    velocity_mps += obstacle_dv_mps_[shape];
  return velocity_mps;
}

double DeformableBody::contactLoss(const StepInputs& inputs, double h) const {
  // Each correction's impulse J = m dx / h against the point's mean velocity over the substep relative
  // to the obstacle, (v0 + v1) / 2 - V: its work, exactly its share of the change of 1/2 m |v - V|^2.
  // A point stopped at a wall loses 1/2 m u^2; a point held still against it loses nothing.
  const auto& m = settings_->mass_kg;
  const auto& x = state_.positions_m;
  const auto& v = state_.velocities_mps;  // still v0, the substep's start
  auto work = [&](uint32_t shape, uint32_t i, const Eigen::Vector3d& moved) {
    const Eigen::Vector3d obstacle = obstacleVelocity(inputs, shape, previous_m_[i]);
    const Eigen::Vector3d mean = 0.5 * (v[i] + (x[i] - previous_m_[i]) / h) - obstacle;
    return (m[i] / h) * moved.dot(mean);
  };
  double loss_J = 0;
  for (const ContactPoint& c : contacts_) loss_J -= work(c.shape, c.point, c.moved_m);
  for (const FaceContact& c : face_contacts_)
    for (int j = 0; j < (c.corners[2] == c.corners[0] ? 2 : 3); ++j)
      loss_J -= work(c.shape, c.corners[j], c.moved_m[j]);
  return loss_J;
}

}  // namespace deform

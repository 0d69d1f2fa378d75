// Contacts between two bodies of a group (body_group_impl.hpp): places on one surface (its control points
// and samples on its triangles) inside the other, or within the contact margin of it, each with the
// nearest place on the other surface.
#include "body_group_impl.hpp"
#include "point_bounds.hpp"
#include "triangle_distance.hpp"

#include <algorithm>
#include <cmath>

namespace deform {
namespace {

// Samples on a control triangle: a grid at most this far apart, 3 to 8 per edge (its interior only; the
// corners are control points). As deform's face contacts against an obstacle (body_contacts.cpp).
constexpr double kSampleSpacing_m = 0.1;
constexpr int kFewestPerEdge = 3, kMostPerEdge = 8;

using detail::highest;
using detail::lowest;

}  // namespace

void BodyGroup::findContacts(std::size_t l) {
  const BodyLink& link = links_[l];
  LinkState& ls = state_[l];
  ls.contacts.clear();
  const std::vector<Eigen::Vector3d>& b_m = body(link.b).state_.positions_m;
  mapped_b_.resize(b_m.size());
  for (std::size_t i = 0; i < b_m.size(); ++i) mapped_b_[i] = toA(link, b_m[i], ls.behind_s);
  const std::vector<Eigen::Vector3d>& a_m = body(link.a).state_.positions_m;
  findContacts(l, 0, a_m, mapped_b_);
  findContacts(l, 1, a_m, mapped_b_);
}

void BodyGroup::samplesOf(uint8_t side, std::size_t l, const std::vector<Eigen::Vector3d>& mapped,
                          const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  // A broad flat front can meet the other body between its control points, and a coarse point pressed
  // into the middle of the other's triangle is resisted by three columns while it has one: samples on
  // both sides make the contact the same seen from either side (they did not change how a side impact
  // splits between the cars at 60 points: docs/CRASH_CALIBRATION.md, "Energy account").
  const DeformableBody& one = body(side == 0 ? links_[l].a : links_[l].b);
  samples_.clear();
  auto inside = [&](const Eigen::Vector3d& p) {
    return !(p.array() < lo.array()).any() && !(p.array() > hi.array()).any();
  };
  for (uint32_t i = 0; i < mapped.size(); ++i)
    if (inside(mapped[i])) samples_.push_back({{i, i, i}, {1, 0, 0}, mapped[i]});
  for (const auto& t : one.settings_->triangles) {
    const Eigen::Vector3d &p0 = mapped[t[0]], &p1 = mapped[t[1]], &p2 = mapped[t[2]];
    if ((p0.cwiseMax(p1).cwiseMax(p2).array() < lo.array()).any() ||
        (p0.cwiseMin(p1).cwiseMin(p2).array() > hi.array()).any())
      continue;
    const double longest = std::max({(p1 - p0).norm(), (p2 - p1).norm(), (p0 - p2).norm()});
    const int k =
        std::clamp(static_cast<int>(std::ceil(longest / kSampleSpacing_m)), kFewestPerEdge, kMostPerEdge);
    for (int i = 1; i < k; ++i)
      for (int j = 1; i + j < k; ++j) {
        const Eigen::Vector3d bary(static_cast<double>(i) / k, static_cast<double>(j) / k,
                                   static_cast<double>(k - i - j) / k);
        const Eigen::Vector3d q = bary[0] * p0 + bary[1] * p1 + bary[2] * p2;
        if (inside(q)) samples_.push_back({t, bary, q});
      }
  }
}

void BodyGroup::findContacts(std::size_t l, uint8_t point_side, const std::vector<Eigen::Vector3d>& a_m,
                             const std::vector<Eigen::Vector3d>& b_m) {
  // Places on one body's surface against the other's control surface, in a's frame: the point of the
  // surface nearest each, and on which side of the surface it lies by the angle-weighted pseudo-normal
  // there (face, edge or corner; Baerentzen & Aanaes 2005: exact for a closed surface, dented or not). A
  // place inside, no deeper than a substep's closing travel plus a crushed layer, or outside within the
  // contact margin, is in contact with its nearest place. The candidates are the places inside the other
  // body's box and, for each triangle near them, those in the grid cells its box covers.
  const BodyLink& link = links_[l];
  LinkState& ls = state_[l];
  DeformableBody& a = body(link.a);
  DeformableBody& b = body(link.b);
  const std::vector<Eigen::Vector3d>& points = point_side == 0 ? a_m : b_m;
  const std::vector<Eigen::Vector3d>& corners = point_side == 0 ? b_m : a_m;
  const uint32_t triangle_index = point_side == 0 ? link.b : link.a;
  const BodySettings& triangle_settings = *body(triangle_index).settings_;
  const auto& triangles = triangle_settings.triangles;
  if (points.empty() || corners.empty() || triangles.empty()) return;
  const double margin_m = std::max(a.params_.contact_margin_m, b.params_.contact_margin_m);
  // How deep a place may be and still be in contact: the frames' closing travel over a substep four times,
  // and 5 cm of layer a crushed surface may hold it in. Not the points' own speeds: a point thrown out fast
  // widened the reach, which found more points inside and threw them out too (a pile of cars at rest blew
  // up in 20 ms).
  const double closing_m = h_s_ * link.velocity_mps.norm();
  const double reach_m = 0.05 + 4.0 * closing_m;
  const double grow_m = std::max(margin_m, reach_m);
  const Eigen::Vector3d corner_lo = lowest(corners), corner_hi = highest(corners);
  samplesOf(point_side, l, points, corner_lo.array() - grow_m, corner_hi.array() + grow_m);
  if (samples_.empty()) return;

  Eigen::Vector3d sample_lo = samples_.front().position_m, sample_hi = sample_lo;
  for (const Sample& s : samples_) {
    sample_lo = sample_lo.cwiseMin(s.position_m);
    sample_hi = sample_hi.cwiseMax(s.position_m);
  }
  // The triangles a sample may be nearest to: those whose box, grown by the reach, meets the samples'.
  auto candidate = [&](const std::array<uint32_t, 3>& tri) {
    const Eigen::Vector3d &q0 = corners[tri[0]], &q1 = corners[tri[1]], &q2 = corners[tri[2]];
    const Eigen::Vector3d lo = q0.cwiseMin(q1).cwiseMin(q2).array() - grow_m;
    const Eigen::Vector3d hi = q0.cwiseMax(q1).cwiseMax(q2).array() + grow_m;
    return !((hi.array() < sample_lo.array()).any() || (lo.array() > sample_hi.array()).any());
  };
  const std::vector<uint32_t>& across = triangle_settings.triangle_across;

  // The surface's pseudo-normals where a sample can meet it: the candidates' faces, their neighbours'
  // across an edge, and the angle-weighted normals of their corners (each summed over every triangle
  // around it, in triangle order). Only those: the acos of every corner of the surface was a tenth of a
  // two-car crash's time at 1,000 points, and the contact region is a small part of the surface.
  const std::size_t triangle_count = triangles.size();
  constexpr uint8_t kNeighbour = 1, kCandidate = 2;  // needed_face_: whose face normal, and why
  needed_face_.assign(triangle_count, 0);
  needed_corner_.assign(corners.size(), 0);
  for (std::size_t t = 0; t < triangle_count; ++t) {
    if (!candidate(triangles[t])) continue;
    needed_face_[t] = kCandidate;
    for (int j = 0; j < 3; ++j) {
      needed_corner_[triangles[t][j]] = 1;
      const uint32_t other = across[3 * t + static_cast<uint32_t>(j)];
      if (other != UINT32_MAX && needed_face_[other] == 0) needed_face_[other] = kNeighbour;
    }
  }
  face_normal_.resize(triangle_count);
  vertex_normal_.assign(corners.size(), Eigen::Vector3d::Zero());
  for (std::size_t t = 0; t < triangle_count; ++t) {
    const auto& tri = triangles[t];
    const bool corner_needed = needed_corner_[tri[0]] || needed_corner_[tri[1]] || needed_corner_[tri[2]];
    if (!needed_face_[t] && !corner_needed) continue;
    const Eigen::Vector3d outward =
        (corners[tri[1]] - corners[tri[0]]).cross(corners[tri[2]] - corners[tri[0]]);
    const double norm = outward.norm();
    face_normal_[t] = norm > 0 ? Eigen::Vector3d(outward / norm) : Eigen::Vector3d::Zero();
    for (int j = 0; j < 3; ++j) {
      if (!needed_corner_[tri[j]]) continue;
      const Eigen::Vector3d e1 = corners[tri[(j + 1) % 3]] - corners[tri[j]];
      const Eigen::Vector3d e2 = corners[tri[(j + 2) % 3]] - corners[tri[j]];
      const double n1 = e1.norm(), n2 = e2.norm();
      if (n1 > 0 && n2 > 0)
        vertex_normal_[tri[j]] += std::acos(std::clamp(e1.dot(e2) / (n1 * n2), -1.0, 1.0)) * face_normal_[t];
    }
  }
  // The grid's cells: the mean longest edge of the surface's triangles at rest (which cells a triangle
  // visits changes nothing found: each sample is tested against every triangle near it, in triangle order;
  // the rest shape's size spares the substep a pass over the whole surface, and cells half the size of
  // twice that edge tested a quarter fewer places: 1.36 -> 1.02 billion instructions in car_to_car at 250
  // points, none fewer at half that).
  if (cell_m_.size() != bodies_.size()) {
    cell_m_.resize(bodies_.size());
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      const BodySettings& settings = *bodies_[i]->settings_;
      const auto& x0 = settings.rest_positions_m;
      double sum_m = 0;
      for (const auto& tri : settings.triangles)
        sum_m += std::max((x0[tri[1]] - x0[tri[0]]).norm(), (x0[tri[2]] - x0[tri[0]]).norm());
      cell_m_[i] = std::max(
          settings.triangles.empty() ? 0.0 : sum_m / static_cast<double>(settings.triangles.size()), 0.05);
    }
  }
  const double cell_m = cell_m_[triangle_index];
  const double inv_cell = 1.0 / cell_m;
  // Cells counted from below the corners' box by more than the reach, so that no sample or grown triangle
  // box has a negative cell (one would have been missed).
  const int pad = 4 + static_cast<int>(std::ceil(grow_m * inv_cell));
  auto cellOf = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector3i(static_cast<int>(std::floor((p.x() - corner_lo.x()) * inv_cell)) + pad,
                           static_cast<int>(std::floor((p.y() - corner_lo.y()) * inv_cell)) + pad,
                           static_cast<int>(std::floor((p.z() - corner_lo.z()) * inv_cell)) + pad);
  };
  auto key = [](const Eigen::Vector3i& c) {
    return (static_cast<uint64_t>(c.x()) << 42) | (static_cast<uint64_t>(c.y()) << 21) |
           static_cast<uint64_t>(c.z());
  };
  cells_.clear();
  for (uint32_t s = 0; s < samples_.size(); ++s) cells_.emplace_back(key(cellOf(samples_[s].position_m)), s);
  std::sort(cells_.begin(), cells_.end());
  best_distance2_.assign(samples_.size(), grow_m * grow_m);
  best_triangle_.assign(samples_.size(), UINT32_MAX);
  best_bary_.resize(samples_.size());

  for (uint32_t t = 0; t < triangles.size(); ++t) {
    if (needed_face_[t] != kCandidate) continue;
    const auto& tri = triangles[t];
    const Eigen::Vector3d &q0 = corners[tri[0]], &q1 = corners[tri[1]], &q2 = corners[tri[2]];
    const Eigen::Vector3d box_lo = q0.cwiseMin(q1).cwiseMin(q2), box_hi = q0.cwiseMax(q1).cwiseMax(q2);
    const Eigen::Vector3d lo = box_lo.array() - grow_m;
    const Eigen::Vector3d hi = box_hi.array() + grow_m;
    const Eigen::Vector3i c_lo = cellOf(lo), c_hi = cellOf(hi);
    for (int cx = std::max(c_lo.x(), 0); cx <= c_hi.x(); ++cx)
      for (int cy = std::max(c_lo.y(), 0); cy <= c_hi.y(); ++cy)
        for (int cz = std::max(c_lo.z(), 0); cz <= c_hi.z(); ++cz) {
          const uint64_t k = key({cx, cy, cz});
          auto it = std::lower_bound(cells_.begin(), cells_.end(), std::make_pair(k, uint32_t{0}));
          for (; it != cells_.end() && it->first == k; ++it) {
            const uint32_t s = it->second;
            const Eigen::Vector3d& p = samples_[s].position_m;
            // The triangle's box is no nearer than the triangle: a box further than the nearest triangle
            // so far cannot win (nor tie: the margin keeps rounding out of it), so its exact distance is
            // not needed.
            const Eigen::Vector3d outside =
                (box_lo - p).cwiseMax(p - box_hi).cwiseMax(Eigen::Vector3d::Zero());
            if (outside.squaredNorm() > best_distance2_[s] * (1 + 1e-9) + 1e-24) continue;
            const Eigen::Vector3d bary = detail::nearestOnTriangle(p, q0, q1, q2);
            const double distance2 = (p - (bary[0] * q0 + bary[1] * q1 + bary[2] * q2)).squaredNorm();
            if (!(distance2 < best_distance2_[s])) continue;  // the first triangle wins a tie
            best_distance2_[s] = distance2;
            best_triangle_[s] = t;
            best_bary_[s] = bary;
          }
        }
  }
  DeformableBody& point_body = point_side == 0 ? a : b;
  DeformableBody& other_body = point_side == 0 ? b : a;
  for (uint32_t s = 0; s < samples_.size(); ++s) {
    const uint32_t t = best_triangle_[s];
    if (t == UINT32_MAX) continue;
    const auto& tri = triangles[t];
    const Eigen::Vector3d& bary = best_bary_[s];
    // The pseudo-normal of the region the nearest place lies in.
    Eigen::Vector3d pseudo = face_normal_[t];
    const int zeros = (bary[0] == 0) + (bary[1] == 0) + (bary[2] == 0);
    if (zeros == 2) {
      pseudo = vertex_normal_[tri[bary[0] != 0 ? 0 : bary[1] != 0 ? 1 : 2]];
    } else if (zeros == 1) {
      const int edge = bary[2] == 0 ? 0 : bary[0] == 0 ? 1 : 2;  // edge j runs from corner j to j + 1
      const uint32_t other = across[3 * t + static_cast<uint32_t>(edge)];
      if (other != UINT32_MAX) pseudo += face_normal_[other];
    }
    const Eigen::Vector3d nearest =
        bary[0] * corners[tri[0]] + bary[1] * corners[tri[1]] + bary[2] * corners[tri[2]];
    const Eigen::Vector3d offset = samples_[s].position_m - nearest;
    const double side = offset.dot(pseudo) < 0 ? -1.0 : 1.0;
    const double distance = side * offset.norm();
    if (distance > margin_m || distance < -reach_m) continue;
    Contact c;
    c.point_side = point_side;
    c.points = samples_[s].corners;
    c.point_bary = samples_[s].bary;
    c.corners = tri;
    c.bary = bary;
    if (offset.norm() > 1e-9)
      c.normal = side * offset.normalized();
    else if (pseudo.norm() > 0)
      c.normal = pseudo.normalized();
    else
      continue;
    ls.contacts.push_back(c);
    if (distance < 0) {
      ls.report.deepest_m = std::max(ls.report.deepest_m, -distance);
      ++point_body.report_.contact_points;
      ++other_body.report_.contact_points;
      ++ls.report.contacts;
    }
  }
}

}  // namespace deform

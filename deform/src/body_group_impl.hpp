#pragma once
// The inside of stepGroup (deform/body_group.hpp), shared by body_group.cpp (the step, the projection and
// the energy account) and body_group_contacts.cpp (finding the contacts).
#include <deform/body_group.hpp>

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace deform {

class BodyGroup {
 public:
  BodyGroup(const std::vector<DeformableBody*>& bodies, const std::vector<BodyLink>& links, double dt_s)
      : bodies_(bodies), links_(links), dt_s_(dt_s) {}

  std::vector<StepReport> step(const std::vector<const StepInputs*>& inputs,
                               std::vector<LinkReport>* link_reports);

 private:
  /// A place on one body's surface (`point_side`: 0 a's, 1 b's), a control point or a sample on a control
  /// triangle, against the nearest place on the other body's surface.
  struct Contact {
    uint8_t point_side = 0;
    /// The place on the point side: sum point_bary_k x_k (a control point: all three the same, (1, 0, 0)).
    std::array<uint32_t, 3> points{0, 0, 0};
    Eigen::Vector3d point_bary{1, 0, 0};
    /// The nearest place on the other side: sum bary_k x_k over a control triangle's corners.
    std::array<uint32_t, 3> corners{0, 0, 0};
    Eigen::Vector3d bary{0, 0, 0};
    Eigen::Vector3d normal{0, 0, 0};    ///< a's frame, out of the other side's body
    Eigen::Vector3d push_x_h{0, 0, 0};  ///< momentum x h given the point side (a's frame)
  };
  /// A place on a surface: corners and barycentric weights (a control point: one corner, (1, 0, 0)).
  struct Sample {
    std::array<uint32_t, 3> corners{0, 0, 0};
    Eigen::Vector3d bary{1, 0, 0};
    Eigen::Vector3d position_m{0, 0, 0};  ///< in a's frame
  };
  struct LinkState {
    std::vector<Contact> contacts;
    double behind_s = 0, start_behind_s = 0;  ///< this substep's end and start, before the step's end [s]
    LinkReport report;
  };

  DeformableBody& body(uint32_t index) const { return *bodies_[index]; }
  /// b's point `p_b` (b's frame) in a's frame, `behind_s` before the step's end: b's frame carried back
  /// along its motion relative to a's, v + w x (p - core_a), to first order (both turn by under a
  /// hundredth of a radian in a step).
  Eigen::Vector3d toA(const BodyLink& link, const Eigen::Vector3d& p_b, double behind_s) const {
    const Eigen::Vector3d p = link.rotation_b_to_a * p_b + link.translation_b_to_a_m;
    if (behind_s == 0) return p;
    const Eigen::Vector3d& core_a = bodies_[link.a]->settings_->core_m;
    return p - behind_s * (link.velocity_mps + link.angular_velocity_radps.cross(p - core_a));
  }
  /// A place sum bary_k x_k of body `in_b ? b : a` in a's frame, its positions `x`.
  Eigen::Vector3d placeOf(const BodyLink& link, bool in_b, const std::vector<Eigen::Vector3d>& x,
                          const std::array<uint32_t, 3>& k, const Eigen::Vector3d& bary,
                          double behind_s) const {
    Eigen::Vector3d p = bary[0] * x[k[0]];
    if (bary[1] != 0) p += bary[1] * x[k[1]];
    if (bary[2] != 0) p += bary[2] * x[k[2]];
    return in_b ? toA(link, p, behind_s) : p;
  }
  /// This substep's contacts of link `l`, both ways.
  void findContacts(std::size_t l);
  /// The places of side `point_side` (0: a's) against the other side's surface; `a_m` and `b_m` the two
  /// bodies' positions in a's frame.
  void findContacts(std::size_t l, uint8_t point_side, const std::vector<Eigen::Vector3d>& a_m,
                    const std::vector<Eigen::Vector3d>& b_m);
  /// Body `side`'s control points and samples on its triangles, within `lo`..`hi` (a's frame), into
  /// samples_; `mapped` its positions in a's frame.
  void samplesOf(uint8_t side, std::size_t l, const std::vector<Eigen::Vector3d>& mapped,
                 const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);
  /// One Jacobi pass over every link's contacts.
  void project();
  static double denominatorOf(const Contact& c, const DeformableBody& pb, const DeformableBody& tb);
  void account(std::size_t l);

  /// A movable obstacle that several bodies of the group touch (StepInputs::contact_keys): each body's
  /// entry (body, its contact index), and this substep's move so far in the common frame [m].
  struct SharedObstacle {
    std::vector<std::pair<uint32_t, uint32_t>> holders;
    Eigen::Vector3d shift_m{0, 0, 0};   ///< this substep's move so far
    Eigen::Vector3d pushes_m{0, 0, 0};  ///< the pushes of this pass's bodies, not yet added
  };
  void findShared(const std::vector<const StepInputs*>& inputs);
  /// Body `i`'s copy of the shared obstacles' move this substep from the common one; its push in this pass
  /// (what its copy moved) added to the pass's pushes; the pass's pushes added to the common move.
  void takeShift(uint32_t i);
  void addShift(uint32_t i);
  void sumShifts();
  /// Every holder's displacement and velocity change as the first holder's (the same up to the rounding of
  /// the frames' turns), at the end of a substep.
  void alignShared();
  std::vector<SharedObstacle> shared_;
  std::vector<Eigen::Matrix3d> to_world_;  ///< per body: StepInputs::frame_to_world

  const std::vector<DeformableBody*>& bodies_;
  const std::vector<BodyLink>& links_;
  double dt_s_;
  double h_s_ = 0;
  std::vector<LinkState> state_;
  // Scratch for findContacts.
  std::vector<Eigen::Vector3d> mapped_b_;  ///< b's positions in a's frame
  std::vector<Sample> samples_;
  std::vector<std::pair<uint64_t, uint32_t>> cells_;
  std::vector<double> best_distance2_;
  std::vector<uint32_t> best_triangle_;
  std::vector<Eigen::Vector3d> best_bary_, face_normal_, vertex_normal_;
  std::vector<uint8_t> needed_face_, needed_corner_;  ///< whose pseudo-normals a sample can meet
  std::vector<double> cell_m_;                        ///< per body: its grid's cell size [m]
  // Scratch for project.
  std::vector<std::vector<double>> counts_;  ///< per body, per point: the contacts it is in this pass
  std::vector<std::vector<Eigen::Vector3d>> corrections_;  ///< per link, per contact (zero: it does not act)
};

}  // namespace deform

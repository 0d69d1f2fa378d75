#pragma once
// Obstacles a control point may not be inside, in the vehicle frame. Exact penetration for primitives;
// a general convex shape given by its support function goes through libccd (MPR penetration).
#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <variant>
#include <vector>

namespace deform {

/// The solid side of a plane: points with normal . x < offset_m are inside.
struct HalfSpaceShape {
  Eigen::Vector3d normal{0, 0, 1};  ///< unit outward normal of the obstacle's surface
  double offset_m = 0;              ///< plane: normal . x = offset_m [m]
};

/// A solid ball.
struct SphereShape {
  Eigen::Vector3d centre_m{0, 0, 0};  ///< [m]
  double radius_m = 0;                ///< [m]
};

/// An oriented box.
struct BoxShape {
  Eigen::Vector3d centre_m{0, 0, 0};                   ///< [m]
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  ///< columns: the box's unit axes in the vehicle frame
  Eigen::Vector3d half_extents_m{0, 0, 0};             ///< half sizes along the axes [m]
};

/// A segment `a_m`-`b_m` swept by a sphere of `radius_m`.
struct CapsuleShape {
  Eigen::Vector3d a_m{0, 0, 0}, b_m{0, 0, 0};  ///< segment ends [m]
  double radius_m = 0;                         ///< [m]
};

/// A solid cylinder with flat ends around the segment `a_m`-`b_m`, stretched across its axis by `sweep_m`
/// (the Minkowski sum of the cylinder and the segment [0, sweep_m]; the sweep's part along the axis is
/// ignored): a post, extended away from the car that meets it. Its push-out is exact: radially from the
/// swept axis, or out through an end.
struct CylinderShape {
  Eigen::Vector3d a_m{0, 0, 0}, b_m{0, 0, 0};  ///< axis ends [m]
  double radius_m = 0;                         ///< [m]
  Eigen::Vector3d sweep_m{0, 0, 0};            ///< extension across the axis [m]
  /// Pushes across its axis only: its ends push nothing, and a point beyond an end is not in contact. A
  /// post cuts the panel that meets its end rather than carrying it up its axis as a ramp would.
  bool across_only = false;
};

/// The point of a convex shape furthest along `direction` [m]; `user` is ConvexSupportShape::user.
using SupportFunction = Eigen::Vector3d (*)(const void* user, const Eigen::Vector3d& direction);

/// Any convex shape given by its support function, as libccd takes it (a plain function and a user
/// pointer, so that shapes copy cheaply).
struct ConvexSupportShape {
  SupportFunction support = nullptr;  ///< required
  const void* user = nullptr;         ///< handed to `support`; must outlive the step that uses the shape
  Eigen::Vector3d centre_m{0, 0, 0};  ///< a point strictly inside the shape [m]
  double bounding_radius_m = 0;       ///< every point of the shape is this close to centre_m [m]
  /// An axis-aligned box holding the whole shape [m], when known (boundingBox; min above max: unknown).
  /// A point or a face outside it (grown by the query's margin) meets nothing, so no MPR runs: another
  /// car's bounding sphere holds half the car that hits it, its box only the contact region.
  Eigen::Vector3d box_min_m{HUGE_VAL, HUGE_VAL, HUGE_VAL};
  Eigen::Vector3d box_max_m{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
};

/// The axis-aligned box of a support shape, from its support points along the six axis directions
/// (exact for any convex shape); sets `box_min_m` and `box_max_m`.
void boundingBox(ConvexSupportShape& shape);

/// True when the box from `low_m` to `high_m`, grown by `margin_m`, lies wholly outside the shape's known
/// bounding box (so nothing in it meets the shape); false when they overlap or the box is unknown.
bool outsideBox(const ConvexSupportShape& shape, const Eigen::Vector3d& low_m, const Eigen::Vector3d& high_m,
                double margin_m);

/// Any obstacle a control point may not be inside.
using ContactShape =
    std::variant<HalfSpaceShape, SphereShape, BoxShape, CapsuleShape, CylinderShape, ConvexSupportShape>;

/// How to push a point out of an obstacle: move it by depth_m along normal.
struct Penetration {
  Eigen::Vector3d normal{0, 0, 1};  ///< unit direction out of the obstacle
  double depth_m = 0;               ///< [m], > 0 when inside, < 0 outside within the query's margin
};

/// True (and `out` filled) when `point_m` is inside `shape` or closer than `margin_m` [m] to its surface;
/// `out.depth_m` is then negative outside (minus the distance). Exact for the primitives (for a box, the
/// distance outside near an edge is that to the nearest face's plane); MPR (ccdMPRPenetration) for a
/// support shape, with the point inflated to a ball of radius margin_m.
bool penetration(const ContactShape& shape, const Eigen::Vector3d& point_m, Penetration& out,
                 double margin_m = 0);

/// A cheap test that a point is surely further than a contact margin from an obstacle, so that most
/// points skip penetration()'s square root and division: beyond a half-space's plane by more than the
/// margin (the n . x - offset penetration() computes, with 1e-9 to spare), or outside a sphere holding a
/// primitive (boundingSphere) grown by twice the margin (a box's test reaches sqrt(3) margins out at its
/// corners), with 1e-5 and 1e-9 m to spare. Never sure for a support shape (its bounding radius is its
/// owner's word) or a box whose axes are not orthonormal within 1e-6. A point it passes still needs the
/// exact test; one it rejects, penetration() would reject too.
class SurelyApart {
 public:
  SurelyApart(const ContactShape& shape, double margin_m);
  bool operator()(const Eigen::Vector3d& point_m) const {
    switch (kind_) {
      case Kind::Plane:
        return normal_or_centre_.dot(point_m) - offset_m_ > limit_;
      case Kind::Ball:
        return (point_m - normal_or_centre_).squaredNorm() > limit_;
      case Kind::Unsure:
        break;
    }
    return false;
  }
  /// Appends to `near`, in order, each point i of [begin, end) not surely apart (operator() false):
  /// four at a time where `wide` and the machine can, with the same answers.
  void listNear(const Eigen::Vector3d* points_m, std::size_t begin, std::size_t end, bool wide,
                std::vector<uint32_t>& near) const;

 private:
  enum class Kind { Unsure, Plane, Ball };
  Kind kind_ = Kind::Unsure;
  Eigen::Vector3d normal_or_centre_{0, 0, 0};
  double offset_m_ = 0, limit_ = 0;
};

/// Narrows the segment `outside_m`-`inside_m` (one end outside `shape`, the other inside) by halving it
/// `bisections` times: both ends move toward where the segment crosses the surface, each keeping its side.
void bisectSurface(const ContactShape& shape, Eigen::Vector3d& outside_m, Eigen::Vector3d& inside_m,
                   int bisections);

/// The point of `shape` furthest along `direction` (its support point) [m]. False for a half-space,
/// which has none (it is unbounded); the direction need not be unit.
bool supportPoint(const ContactShape& shape, const Eigen::Vector3d& direction, Eigen::Vector3d& out_m);

/// How a post pushes (CylinderShape::across_only): `out` becomes the part of the unit `normal` across the
/// unit `axis`, made unit, when it is at least half of it (the normal at least 30 degrees off the axis);
/// false for a normal closer to the axis (a post's end, which pushes nothing).
bool acrossAxis(const Eigen::Vector3d& normal, const Eigen::Vector3d& axis, Eigen::Vector3d& out);

/// True when penetration()'s depth for `shape` is minus the Euclidean distance outside it, so that it
/// changes by at most the distance a point moves: a sphere, a capsule, a cylinder (swept or not), and a
/// box whose axes are orthonormal within 1e-9 (its depth outside is the largest distance beyond a face
/// pair, which is no more than the distance and moves no faster). False for a half-space (unbounded,
/// tested otherwise) and a support shape (MPR's depth).
bool distanceIsLipschitz(const ContactShape& shape);
/// A sphere holding all of `shape` (centre, radius) [m]. False for a half-space.
bool boundingSphere(const ContactShape& shape, Eigen::Vector3d& centre_m, double& radius_m);

/// The convex hull of a point set (e.g. a jersey barrier's vertices) as a support shape. Owns its
/// points; the shapes it hands out refer to it, so it must outlive them.
class ConvexPoints {
 public:
  /// Throws InputError for no points or a non-finite one.
  explicit ConvexPoints(std::vector<Eigen::Vector3d> points_m);
  ConvexSupportShape shape() const;  ///< the hull as a support shape (refers to this object)

 private:
  static Eigen::Vector3d support(const void* user, const Eigen::Vector3d& direction);
  std::vector<Eigen::Vector3d> points_m_;  ///< [m]
  Eigen::Vector3d centre_m_{0, 0, 0};      ///< mean of the points [m]
  double radius_m_ = 0;                    ///< furthest point from the centre [m]
};

/// Throws InputError naming `field` for a non-finite value, a zero normal, a negative radius or extent,
/// or a support shape without a support function.
void checkContactShape(const ContactShape& shape, const char* field);

}  // namespace deform

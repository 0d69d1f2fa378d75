#pragma once
// What a deformable car hits, as deform's contact shapes in its vehicle frame (the crush coupling,
// DESIGN.md section 5). Each shape is swept a little along the car's motion relative to it, away from
// the car: a control point that a fast obstacle overran during the step (up to |v| dt deep) then still
// leaves through the near face, never through the far side of a thin wall (no tunnelling of the dent).
#include <vehicle/obstacle_shape.hpp>

#include <deform/contact_shapes.hpp>

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace vehicle {

/// An obstacle shape (vehicle frame) plus a sweep: the support function of the Minkowski sum of the shape
/// and the segments [0, sweep_m] and [0, down_m] (libccd / MPR input for shapes without an exact deform
/// primitive).
struct SweptShape {
  ObstacleShape shape;               ///< vehicle frame
  Eigen::Vector3d sweep_m{0, 0, 0};  ///< extension away from the car [m]
  Eigen::Vector3d down_m{0, 0, 0};   ///< extension into the ground, for an obstacle standing on it [m]
  static Eigen::Vector3d support(const void* user, const Eigen::Vector3d& direction);
};

/// Keeps the swept shapes alive while deform steps with the contact shapes that point into them.
class CrushShapes {
 public:
  void clear();
  /// Adds `shape` (vehicle frame) extended by `sweep_m` and by `down_m` (into the ground under an obstacle
  /// standing on it, so a point deep in a wall is never pushed out under it); boxes stay exact primitives
  /// (extended along their axes closest to the extensions), the rest become support shapes. A `post`
  /// (a fixed cylinder or capsule) becomes deform's cylinder (exact push-out, see crush_shapes.cpp). A
  /// `surface` obstacle (another car's body) is also met between the control points (deform's face contacts,
  /// StepInputs::surface_contact).
  void add(const ObstacleShape& shape, const Eigen::Vector3d& sweep_m, const Eigen::Vector3d& down_m,
           bool post = false, bool surface = false);
  const std::vector<deform::ContactShape>& shapes() const { return shapes_; }
  /// One flag per shape: met between the control points too.
  const std::vector<uint8_t>& surfaceFlags() const { return surface_; }
  /// The same obstacles without the extensions (for measuring what is left inside them).
  const std::vector<deform::ContactShape>& exactShapes() const { return exact_; }

 private:
  std::vector<std::unique_ptr<SweptShape>> swept_;  ///< stable addresses for the support pointers
  std::vector<deform::ContactShape> shapes_;
  std::vector<uint8_t> surface_;  ///< per shapes_ entry
  std::vector<deform::ContactShape> exact_;
};

}  // namespace vehicle

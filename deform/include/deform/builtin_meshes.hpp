#pragma once
// Built-in meshes made by our own code: the default car, a drinks can and a box (part of deform_io, the
// types VehicleModel and WheelPart are plain data every layer uses). Deterministic: the
// same parameters give bit-identical meshes on every run.
#include <deform/mesh.hpp>

#include <string>
#include <vector>

namespace deform {

/// A wheel drawn with a car but not part of its deformable body, in the vehicle frame.
struct WheelPart {
  Eigen::Vector3d centre_m{0, 0, 0};  ///< hub centre [m]
  double radius_m = 0.32;             ///< tyre outer radius [m]
  double width_m = 0.22;              ///< tyre width [m]
  bool steered = false;               ///< front wheels steer
};

/// A vehicle as loaded or generated: the deformable body and the parts that are not deformed.
struct VehicleModel {
  Mesh body;                      ///< deformable render mesh
  std::vector<WheelPart> wheels;  ///< empty when the source has none
  std::string source;             ///< where it came from, for messages
};

/// Passenger car about 4.8 x 1.8 x 1.45 m (bonnet, windscreen, cabin, boot, wheel arches), closed
/// surface, with about `target_vertices` vertices (1,000 to 4,000,000+). Four wheels as WheelParts.
VehicleModel makeSedan(std::size_t target_vertices = 20000);

/// A 330 ml drinks can (radius 33 mm, height 122 mm), closed, about `target_vertices` vertices.
Mesh makeCan(std::size_t target_vertices = 4000);

/// A closed box of the given size [m], centred on the origin, faces subdivided to about
/// `target_vertices` vertices.
Mesh makeBox(const Eigen::Vector3d& size_m, std::size_t target_vertices = 600);

/// A closed wheel (cylinder around the Y axis) for drawing a WheelPart, centred on the origin.
Mesh makeWheelMesh(double radius_m, double width_m, int segments = 32);

/// Parses "builtin:NAME[?key=value&...]" (sedan: vertices; can: vertices; box: x, y, z, vertices)
/// and builds it. Throws InputError naming the spec and the key for an unknown name, key or value.
/// Defaults: sedan 20,000 vertices, can 4,000, box 1 x 1 x 1 m with 600; `vertices` must lie in
/// [100, 50,000,000] and box sizes in (0, 1000] m. The model's `source` is the spec.
VehicleModel makeBuiltin(const std::string& spec);

/// True when `spec` starts with "builtin:".
bool isBuiltinSpec(const std::string& spec);

}  // namespace deform

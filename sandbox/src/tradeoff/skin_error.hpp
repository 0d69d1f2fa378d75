#pragma once
// The skin alone (`sandbox tradeoff --skin-only`), separated from the physics: the built-in sedan's
// control mesh at each N moved by known smooth fields (tradeoff/known_fields.hpp), the render mesh
// deformed by the skin, and compared with the field applied to every render vertex directly.
#include <cstddef>
#include <string>
#include <vector>

namespace sandbox {

/// One skin (N, K, alpha, method) on one field, measured over the render mesh.
struct SkinErrorRow {
  std::string field;               ///< "bend", "twist", "crush", "affine", "wall_crash"
  std::string method;              ///< "idw", "mls" or "spline" (k 0 and alpha 0: every point, no power)
  std::size_t control_points = 0;  ///< N as built (within 5 % of the target)
  std::size_t target_points = 0;   ///< N asked for
  std::size_t k = 0;               ///< influences per vertex
  double alpha = 0;                ///< inverse-distance power
  double rms_error_m = 0;          ///< RMS over the render vertices of |skinned - exact| [m]
  double max_error_m = 0;          ///< largest |skinned - exact| [m]
  double field_max_m = 0;          ///< largest |u| of the field over the render vertices [m], for scale
};

struct SkinErrorOptions {
  std::size_t vertices = 20000;  ///< render-mesh vertices of builtin:sedan
  std::vector<std::size_t> control_points = {60, 120, 250, 500, 1000, 2000};
  std::vector<std::size_t> k = {4, 8, 16};
  std::vector<double> alpha = {2, 3.5, 6};
  /// Control points of the finest model whose wall-crash dent is the field "wall_crash"
  /// (tradeoff/crash_field.hpp); 0 leaves that field out.
  std::size_t crash_points = 2000;
  /// Fewer N (60, 250, 1000).
  static SkinErrorOptions quick();
};

/// Every field for every N, K, alpha and method, N-major. Progress lines go to stdout.
std::vector<SkinErrorRow> runSkinError(const SkinErrorOptions& options);

}  // namespace sandbox

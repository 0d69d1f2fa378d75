#pragma once
// Loading a vehicle from a file any format assimp reads (glTF/GLB, OBJ, DAE, FBX, PLY, STL) or from a
// "builtin:" spec. Part of deform_io (links assimp); the deform library itself does not need it.
#include <deform/builtin_meshes.hpp>

#include <optional>
#include <string>

namespace deform {

/// Which file axis points up / forward, converted to the vehicle frame (Z up, X forward).
enum class Axis { PosX, NegX, PosY, NegY, PosZ, NegZ };

/// Parses "x", "-x", "+y", "z", ... Throws InputError naming `field` for anything else.
Axis parseAxis(const std::string& text, const std::string& field);

struct ImportOptions {
  double scale = 1.0;                 ///< multiplies file units to get metres; must be > 0
  std::optional<Axis> up;             ///< file's up axis; default per format (glTF: +Y, others: +Z)
  std::optional<Axis> forward;        ///< file's forward axis; default per format (glTF: +Z, others: +X)
};

/// Every mesh of the file with its node transforms (instances expanded), positions welded, scaled to
/// metres and rotated into the vehicle frame. "builtin:..." specs are generated instead (scale and axes
/// still apply). Throws InputError naming the file and the problem: missing file, unreadable format, no
/// triangles, non-finite coordinates, zero extent, scale <= 0.
VehicleModel loadVehicleModel(const std::string& spec, const ImportOptions& options = {});

}  // namespace deform

#include "mesh_options.hpp"

#include <deform/error.hpp>

#include <cmath>

namespace sandbox {

void MeshLoadFlags::addTo(CLI::App& command) {
  command.add_option("--scale", scale, "Multiplies file units to get metres (e.g. 0.0254 for inches)");
  command.add_option("--up", up, "File's up axis: x, -x, y, -y, z, -z (default per format)");
  command.add_option("--forward", forward, "File's forward axis (default per format)");
}

deform::ImportOptions MeshLoadFlags::importOptions() const {
  if (!std::isfinite(scale) || scale <= 0)
    throw deform::InputError("--scale: must be a finite number above zero (got " + std::to_string(scale) +
                             ")");
  deform::ImportOptions options;
  options.scale = scale;
  if (!up.empty()) options.up = deform::parseAxis(up, "--up");
  if (!forward.empty()) options.forward = deform::parseAxis(forward, "--forward");
  return options;
}

}  // namespace sandbox

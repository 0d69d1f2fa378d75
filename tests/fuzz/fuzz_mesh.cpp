// libFuzzer target: the mesh importer as `sandbox mesh info FILE` uses it (deform::loadVehicleModel on a
// file), one binary per format: DEFORM_FUZZ_MESH_EXT is the file extension the input is saved under. A
// small accepted mesh also gets its control mesh built (the convex hull through qhull), as every scene
// does next. A refused input (deform::InputError) is the importer working; anything else is a finding.
#include <deform/control_mesh.hpp>
#include <deform/error.hpp>
#include <deform/mesh_import.hpp>

#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#ifndef DEFORM_FUZZ_MESH_EXT
#error "DEFORM_FUZZ_MESH_EXT must name the format's extension, e.g. \"obj\""
#endif

#include "cpu_budget.hpp"

namespace {

/// The file each input is written to (the importer reads files, as the CLI does); removed at exit.
const std::string& inputPath() {
  static const std::string path = [] {
    const std::string p = (std::filesystem::temp_directory_path() /
                           ("deform_fuzz_" + std::to_string(::getpid()) + "." + DEFORM_FUZZ_MESH_EXT))
                              .string();
    std::atexit([] { std::remove(inputPath().c_str()); });
    return p;
  }();
  return path;
}

/// Invariants of every imported mesh (mesh_import.hpp): finite positions, triangles of three distinct
/// vertices in range, one unit normal per vertex. A hard stop when one fails.
void checkImported(const deform::Mesh& mesh) {
  if (mesh.triangles.empty() || mesh.normals.size() != mesh.positions_m.size()) std::abort();
  for (const Eigen::Vector3f& p : mesh.positions_m)
    if (!p.allFinite()) std::abort();
  for (const deform::Triangle& t : mesh.triangles) {
    for (std::uint32_t v : t)
      if (v >= mesh.positions_m.size()) std::abort();
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const fuzz_support::CpuBudget budget;
  {
    std::ofstream out(inputPath(), std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    // assimp reads in a child process: a file it hangs on is refused after a second of the child's CPU
    // time (the product's limit is 120 s), the budget above being this process's own.
    deform::ImportOptions options;
    options.importer_cpu_limit_s = 1;
    const deform::VehicleModel model = deform::loadVehicleModel(inputPath(), options);
    checkImported(model.body);
    if (model.body.positions_m.size() <= 2000) {
      std::vector<Eigen::Vector3d> points;
      points.reserve(model.body.positions_m.size());
      for (const Eigen::Vector3f& p : model.body.positions_m) points.push_back(p.cast<double>());
      const deform::ControlMesh control = deform::buildControlMesh(points, 30, inputPath().c_str());
      if (control.points_m.size() != 30) std::abort();  // LodMethod::Even: exactly the target
    }
  } catch (const deform::InputError&) {
    // refused with a message naming the file: what bad input must get
  }
  return 0;
}

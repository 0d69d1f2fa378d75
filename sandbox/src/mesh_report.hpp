#pragma once
// What `sandbox mesh info` measures of a mesh: its size, its control mesh, the mass split and the checks
// of its embedding.
#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>
#include <deform/skin.hpp>

#include <nlohmann/json.hpp>

namespace sandbox {

struct MeshReportOptions {
  std::size_t control_points = 60;
  deform::LodMethod lod = deform::LodMethod::Even;
  double vehicle_mass_kg = 1500;
  deform::SkinOptions skin;
};

/// Builds the control mesh, masses and skin of `model` and measures them. Throws deform::InputError
/// for input the method cannot take.
nlohmann::ordered_json meshReport(const deform::VehicleModel& model, const MeshReportOptions& options);

/// The same report as aligned text lines.
std::string formatMeshReport(const nlohmann::ordered_json& report);

}  // namespace sandbox

#include "grid/full_resolution.hpp"

#include "elapsed.hpp"

#include <deform/body_settings.hpp>
#include <deform/control_mesh.hpp>
#include <deform/masses.hpp>

#include <chrono>
#include <memory>

namespace sandbox {

GridRow fullResolutionRow(const deform::Mesh& mesh, double mass_kg, const StepCostOptions& step) {
  const auto start = Clock::now();
  deform::ControlMesh surface;
  surface.points_m.reserve(mesh.positions_m.size());
  for (const auto& p : mesh.positions_m) surface.points_m.push_back(p.cast<double>());
  surface.triangles = mesh.triangles;
  deform::finishControlMesh(surface);  // edges with their wings, volume, centre of mass
  deform::MassSplit masses;
  masses.point_mass_kg.assign(surface.points_m.size(),
                              mass_kg / static_cast<double>(surface.points_m.size()));
  const auto settings = std::make_shared<const deform::BodySettings>(
      deform::createBodySettings(surface, masses, deform::BodyDescription{}));
  GridRow row;
  row.method = "full-resolution XPBD";
  row.body_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  row.vertices = mesh.positions_m.size();
  row.control_points = settings->pointCount();
  row.constraints = settings->constraintCount();
  row.step_ms = measureStepCost(settings, step).us_per_step * 1e-3;
  return row;
}

}  // namespace sandbox

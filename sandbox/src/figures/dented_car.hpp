#pragma once
// A car after a scene, its render mesh dented by the control points through a skin, coloured by how far
// each vertex moved for good (red most, blue none), and rendered from named views. Shared by the crash
// figures (crash_figures.cpp) and the skin comparison (skin_figures.cpp).
#include <deform/builtin_meshes.hpp>
#include <deform/skin.hpp>
#include <scenes/scene_run.hpp>

#include <optional>
#include <string>
#include <vector>

#include "figures.hpp"
#include "render/png_io.hpp"

namespace sandbox::figures {

struct DentedCar {
  deform::VehicleModel model;                    ///< the car as loaded, undamaged
  deform::Mesh dented;                           ///< its body after the scene (vehicle frame)
  std::vector<deform::WheelPart> dented_wheels;  ///< its wheels, carried with the bodywork around them
  std::vector<Eigen::Vector3f> colours;          ///< permanent displacement, blue none .. red most
  vehicle::CrashMetrics metrics;
  std::size_t control_points = 0;
  deform::SkinMethod skin_method = deform::SkinMethod::idw;  ///< the skin that dented the render mesh
};

/// Car 0 of `run` (played as far as wanted) dented by its control points through the car's skin, or
/// through a skin of `method` when given (the same alpha and K).
DentedCar dentCar(scenes::SceneRun& run, std::optional<deform::SkinMethod> method = std::nullopt);

/// Plays `scene` (with `overrides`) to its end and dents car 0's render mesh by its control points.
DentedCar playAndDent(const std::string& scene, const std::vector<std::string>& overrides);

/// The dented car, standing on the ground, from several named views (render/camera.hpp presets).
std::vector<render::Image> views(const DentedCar& car, const FigureOptions& o,
                                 const std::vector<std::string>& cameras);

/// Writes `image` as `file` in the figure folder.
void save(const FigureOptions& o, const std::string& file, const render::Image& image);

}  // namespace sandbox::figures

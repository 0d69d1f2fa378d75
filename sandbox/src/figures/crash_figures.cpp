// The paper's crash figures: a scene played with our runner, the render mesh following the control
// points, coloured by how far each vertex moved for good (red most, blue none).
#include <cstdio>

#include "dented_car.hpp"
#include "figures.hpp"
#include "image_tiles.hpp"

namespace sandbox::figures {

Figure wallCrashFigure(const FigureOptions& o) {
  const DentedCar car = playAndDent("wall_crash", {});
  save(o, "wall_crash.png", tileImages(views(car, o, {"quarter", "side", "top"}), 3));
  char caption[640];
  std::snprintf(
      caption, sizeof caption,
      "`sandbox run wall_crash`: the built-in sedan (%zu vertices, %zu control points, crush coupling, "
      "%s skin) into a rigid wall at %.1f km/h, after the rebound; coloured by permanent displacement (red "
      "%.2f m, blue none). Residual crush %.3f m averaged over six stations (largest %.3f m), "
      "restitution %.2f, plastic work %.0f kJ of %.0f kJ.",
      car.dented.positions_m.size(), car.control_points, deform::skinMethodName(car.skin_method),
      3.6 * car.metrics.impact_speed_mps, car.metrics.max_deviation_m, car.metrics.residual_crush_m,
      car.metrics.max_residual_crush_m, car.metrics.restitution, car.metrics.energy.plastic_work_J / 1e3,
      car.metrics.energy.kinetic_initial_J / 1e3);
  return {"wall_crash.png", caption};
}

Figure minorHitsFigure(const FigureOptions& o) {
  // post_bumps as shipped (a tree, a shrub, then a bollard) with the 900,000-vertex car.
  const DentedCar car = playAndDent("post_bumps", {"vehicle.mesh=\"builtin:sedan?vertices=900000\"",
                                                   "vehicle.deformation.control_points=60"});
  save(o, "minor_hits.png", tileImages(views(car, o, {"quarter", "front"}), 2));
  char caption[720];
  std::snprintf(
      caption, sizeof caption,
      "`sandbox run post_bumps --set vehicle.mesh=builtin:sedan?vertices=900000`: a %zu-vertex sedan with "
      "%zu control points (%s skin) after knocking over a small tree and a shrub (free obstacles that the "
      "body pushes by their mass and that dent it by their contacts) and nudging a 0.2 m steel bollard at "
      "15 km/h; coloured by permanent "
      "displacement (red %.3f m, blue none), residual crush %.3f m; the car went %.2f m into what it hit "
      "(the face contacts dent the surface between the control points).",
      car.dented.positions_m.size(), car.control_points, deform::skinMethodName(car.skin_method),
      car.metrics.max_deviation_m, car.metrics.max_residual_crush_m, car.metrics.max_dynamic_crush_m);
  return {"minor_hits.png", caption};
}

}  // namespace sandbox::figures

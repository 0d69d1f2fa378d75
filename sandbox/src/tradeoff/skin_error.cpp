#include "tradeoff/skin_error.hpp"

#include "tradeoff/crash_field.hpp"
#include "tradeoff/known_fields.hpp"

#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>
#include <deform/skin.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sandbox {

SkinErrorOptions SkinErrorOptions::quick() {
  SkinErrorOptions o;
  o.control_points = {60, 250, 1000};
  return o;
}

std::vector<SkinErrorRow> runSkinError(const SkinErrorOptions& options) {
  const deform::VehicleModel car = deform::makeSedan(options.vertices);
  const std::vector<Eigen::Vector3f>& rest = car.body.positions_m;
  std::vector<KnownField> fields = knownFields(deform::boundingBox(car.body));
  if (options.crash_points > 0) fields.push_back(wallCrashField(options.crash_points));
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : rest) points.push_back(p.cast<double>());
  // The exact answer: each field applied to every render vertex.
  std::vector<std::vector<Eigen::Vector3d>> exact_m(fields.size());
  std::vector<double> field_max_m(fields.size(), 0.0);
  for (std::size_t f = 0; f < fields.size(); ++f) {
    for (const auto& p : points) {
      exact_m[f].push_back(fields[f].displacement_m(p));
      field_max_m[f] = std::max(field_max_m[f], exact_m[f].back().norm());
    }
  }
  std::vector<SkinErrorRow> rows;
  std::vector<Eigen::Vector3f> skinned(rest.size());
  for (const std::size_t target : options.control_points) {
    const deform::ControlMesh control = deform::buildControlMesh(points, target, "builtin:sedan");
    // The skinned mesh against field f applied to every vertex, as a row.
    const auto measured = [&](std::size_t f, const char* method, std::size_t k, double alpha) {
      double sum_m2 = 0, max_m = 0;
      for (std::size_t j = 0; j < rest.size(); ++j) {
        const Eigen::Vector3d skinned_shift = (skinned[j] - rest[j]).cast<double>();
        const double e = (skinned_shift - exact_m[f][j]).norm();
        sum_m2 += e * e;
        max_m = std::max(max_m, e);
      }
      return SkinErrorRow{fields[f].name,
                          method,
                          control.points_m.size(),
                          target,
                          k,
                          alpha,
                          std::sqrt(sum_m2 / static_cast<double>(rest.size())),
                          max_m,
                          field_max_m[f]};
    };
    std::printf("skin error: N = %zu (%zu control points)\n", target, control.points_m.size());
    std::fflush(stdout);
    std::vector<std::vector<Eigen::Vector3d>> moved(fields.size());  // d_i = u(c_i0)
    for (std::size_t f = 0; f < fields.size(); ++f)
      for (const auto& c : control.points_m) moved[f].push_back(fields[f].displacement_m(c));
    // The spline uses every point whatever K and alpha: one row per field, k 0 (dense) and alpha 0.
    if (control.points_m.size() <= deform::kSplineMostControlPoints) {
      deform::SkinOptions spline;  // K and alpha are not read
      spline.method = deform::SkinMethod::spline;
      const deform::Skin skin = deform::Skin::build(rest, control.points_m, spline);
      for (std::size_t f = 0; f < fields.size(); ++f) {
        skin.deform(rest.data(), moved[f].data(), skinned.data());
        rows.push_back(measured(f, "spline", 0, 0.0));
      }
    }
    for (const deform::SkinMethod method : {deform::SkinMethod::idw, deform::SkinMethod::mls}) {
      for (const std::size_t k : options.k) {
        for (const double alpha : options.alpha) {
          const deform::Skin skin = deform::Skin::build(rest, control.points_m, {alpha, k, 0, method});
          for (std::size_t f = 0; f < fields.size(); ++f) {
            skin.deform(rest.data(), moved[f].data(), skinned.data());
            rows.push_back(measured(f, deform::skinMethodName(method), k, alpha));
          }
        }
      }
    }
  }
  return rows;
}

}  // namespace sandbox

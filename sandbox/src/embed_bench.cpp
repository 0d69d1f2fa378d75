#include "embed_bench.hpp"

#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>
#include <deform/error.hpp>
#include <deform/skin.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

namespace sandbox {
namespace {

using Clock = std::chrono::steady_clock;

template <class Fn>
double medianMs(int repetitions, Fn&& fn) {
  fn();  // warm caches and page tables
  std::vector<double> ms;
  for (int r = 0; r < repetitions; ++r) {
    auto start = Clock::now();
    fn();
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
  }
  std::nth_element(ms.begin(), ms.begin() + static_cast<std::ptrdiff_t>(ms.size() / 2), ms.end());
  return ms[ms.size() / 2];
}

/// The simplest sparse loop a user might write first: one struct per vertex holding its position and its
/// influences, accumulated in Eigen doubles.
struct Influence {
  uint32_t control = 0;
  float weight = 0;
};
struct SkinnedVertex {
  Eigen::Vector3f rest_m;
  std::vector<Influence> influences;
};

}  // namespace

nlohmann::ordered_json runEmbedBench(const EmbedBenchOptions& o) {
  if (o.vertices < 1000) throw deform::InputError("--vertices: at least 1000");
  if (o.control_points < 4) throw deform::InputError("--control-points: at least 4");
  if (o.k > 65536) throw deform::InputError("--k: at most 65536 (0 means dense)");
  if (o.repetitions < 1) throw deform::InputError("--repetitions: at least 1");
  const unsigned threads = deform::resolveThreads(o.threads);

  const deform::VehicleModel car = deform::makeSedan(o.vertices);
  const auto& rest = car.body.positions_m;
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : rest) points.push_back(p.cast<double>());
  const deform::ControlMesh control = deform::buildControlMesh(points, o.control_points, "builtin:sedan");
  Clock::time_point build_start = Clock::now();
  const deform::Skin skin = deform::Skin::build(rest, control.points_m, {o.alpha, o.k, threads});
  const double build_ms = std::chrono::duration<double, std::milli>(Clock::now() - build_start).count();

  // A dent-like displacement field: every control point moved, so no work is skipped.
  std::vector<Eigen::Vector3d> displacement(control.points_m.size());
  for (std::size_t i = 0; i < displacement.size(); ++i)
    displacement[i] =
        -0.05 * control.points_m[i].normalized() * (1.0 + 0.1 * std::sin(static_cast<double>(i)));
  std::vector<Eigen::Vector3f> out(rest.size());
  const double ms =
      medianMs(o.repetitions, [&] { skin.deform(rest.data(), displacement.data(), out.data(), threads); });

  // Streaming copy, same threads: the bandwidth bound. Source and destination of 128 MB each at least,
  // four times a large last-level cache, so the copy runs from memory as the pass does.
  const std::size_t bytes_per_vertex = skin.bytesPerVertex();
  const std::size_t copy_floats =
      std::max<std::size_t>(rest.size() * bytes_per_vertex / 8, std::size_t{32} << 20);
  std::vector<float> src(copy_floats, 1.0f), dst(copy_floats, 0.0f);
  const double copy_ms = medianMs(o.repetitions, [&] {
    deform::parallelFor(copy_floats, threads, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) dst[i] = src[i];
    });
  });
  const double copy_bytes_per_ms = 2.0 * static_cast<double>(copy_floats * sizeof(float)) / copy_ms;

  // Baseline: array of structs, Eigen double accumulation, same threads.
  std::vector<SkinnedVertex> aos(rest.size());
  for (std::size_t j = 0; j < rest.size(); ++j) {
    aos[j].rest_m = rest[j];
    for (std::size_t k = 0; k < skin.influences(); ++k)
      aos[j].influences.push_back({skin.slotIndex(j, k), skin.slotWeight(j, k)});
  }
  std::vector<Eigen::Vector3f> out_aos(rest.size());
  const double aos_ms = medianMs(o.repetitions, [&] {
    deform::parallelFor(aos.size(), threads, [&](std::size_t b, std::size_t e) {
      for (std::size_t j = b; j < e; ++j) {
        Eigen::Vector3d v = aos[j].rest_m.cast<double>();
        for (const Influence& inf : aos[j].influences) v += inf.weight * displacement[inf.control];
        out_aos[j] = v.cast<float>();
      }
    });
  });
  double disagreement_m = 0;
  for (std::size_t j = 0; j < out.size(); ++j)
    disagreement_m = std::max(disagreement_m, static_cast<double>((out[j] - out_aos[j]).norm()));

  // The same pass over affine moving-least-squares weights (deform/skin.hpp, SkinMethod::mls).
  build_start = Clock::now();
  const deform::Skin mls =
      deform::Skin::build(rest, control.points_m, {o.alpha, o.k, threads, deform::SkinMethod::mls});
  const double mls_build_ms = std::chrono::duration<double, std::milli>(Clock::now() - build_start).count();
  const double mls_ms =
      medianMs(o.repetitions, [&] { mls.deform(rest.data(), displacement.data(), out.data(), threads); });

  const double pass_bytes_per_ms = static_cast<double>(bytes_per_vertex * rest.size()) / ms;
  nlohmann::ordered_json r;
  r["vertices"] = rest.size();
  r["control_points"] = control.points_m.size();
  r["k"] = skin.influences();
  r["threads"] = threads;
  r["alpha"] = o.alpha;
  r["repetitions"] = o.repetitions;
  r["ms"] = ms;
  r["vertices_per_ms"] = static_cast<double>(rest.size()) / ms;
  r["bytes_per_vertex"] = bytes_per_vertex;
  r["gb_per_s"] = pass_bytes_per_ms / 1e6;
  r["copy_gb_per_s"] = copy_bytes_per_ms / 1e6;
  r["bandwidth_fraction"] = pass_bytes_per_ms / copy_bytes_per_ms;
  r["baseline_aos_ms"] = aos_ms;
  r["speedup_vs_aos"] = aos_ms / ms;
  r["aos_max_difference_m"] = disagreement_m;
  r["skin_build_ms"] = build_ms;
  r["skin_bytes"] = skin.memoryBytes();
  r["mls"] = {{"skin_build_ms", mls_build_ms},
              {"ms", mls_ms},
              {"vertices_per_ms", static_cast<double>(rest.size()) / mls_ms}};
  return r;
}

}  // namespace sandbox

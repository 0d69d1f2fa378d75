#include "embed_bench.hpp"

#include "elapsed.hpp"

#include "embed_plain.hpp"

#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>
#include <deform/error.hpp>
#include <deform/skin.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace sandbox {
namespace {

template <class Fn>
double medianMs(int repetitions, Fn&& fn) {
  fn();  // warm caches and page tables
  std::vector<double> ms;
  for (int r = 0; r < repetitions; ++r) {
    auto start = Clock::now();
    fn();
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
  }
  return median(ms);
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
  if (o.rounds < 1) throw deform::InputError("--rounds: at least 1");
  if (o.control_points > 65536)
    throw deform::InputError("--control-points: at most 65536 (the plain kernel)");
  const unsigned threads = deform::resolveThreads(o.threads);

  const deform::VehicleModel car = deform::makeSedan(o.vertices);
  const auto& rest = car.body.positions_m;
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : rest) points.push_back(p.cast<double>());
  const deform::ControlMesh control = deform::buildControlMesh(points, o.control_points, "builtin:sedan");
  const auto buildSkin = [&](deform::SkinMethod method, deform::SkinLayout layout, double* build_ms) {
    const Clock::time_point start = Clock::now();
    deform::Skin built = deform::Skin::build(rest, control.points_m, {o.alpha, o.k, threads, method, layout});
    if (build_ms) *build_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    return built;
  };
  double build_ms = 0, mls_build_ms = 0;
  const deform::Skin skin = buildSkin(deform::SkinMethod::idw, deform::SkinLayout::compact, &build_ms);
  const deform::Skin skin_float =
      buildSkin(deform::SkinMethod::idw, deform::SkinLayout::float_weights, nullptr);
  const deform::Skin mls = buildSkin(deform::SkinMethod::mls, deform::SkinLayout::compact, &mls_build_ms);
  const deform::Skin mls_float =
      buildSkin(deform::SkinMethod::mls, deform::SkinLayout::float_weights, nullptr);
  if (o.spline && control.points_m.size() > deform::kSplineMostControlPoints)
    throw deform::InputError("--spline: at most " + std::to_string(deform::kSplineMostControlPoints) +
                             " control points (deform::kSplineMostControlPoints)");
  double spline_build_ms = 0;
  const std::optional<deform::Skin> spline =
      o.spline ? std::optional(
                     buildSkin(deform::SkinMethod::spline, deform::SkinLayout::compact, &spline_build_ms))
               : std::nullopt;

  // A dent-like displacement field: every control point moved, so no work is skipped.
  std::vector<Eigen::Vector3d> displacement(control.points_m.size());
  for (std::size_t i = 0; i < displacement.size(); ++i)
    displacement[i] =
        -0.05 * control.points_m[i].normalized() * (1.0 + 0.1 * std::sin(static_cast<double>(i)));
  std::vector<PlainPoint> plain_displacement;
  for (const auto& d : displacement)
    plain_displacement.push_back(
        {static_cast<float>(d.x()), static_cast<float>(d.y()), static_cast<float>(d.z())});

  // The passes, alternated round by round so that each round's ratio pairs passes measured moments apart
  // (the machine is shared: its state moves the figures more than the code does).
  const PlainSkin plain = makePlainSkin(skin_float, rest);
  std::vector<PlainPoint> out_plain(rest.size());
  std::vector<Eigen::Vector3f> out(rest.size()), out_mls(rest.size()), out_other(rest.size());
  struct Pass {
    const char* name;
    std::function<void()> run;
    std::vector<double> ms;
  };
  std::vector<Pass> passes = {
      {"plain", [&] { plainSkinPass(plain, plain_displacement, out_plain, threads); }, {}},
      {"idw", [&] { skin.deform(rest.data(), displacement.data(), out.data(), threads); }, {}},
      {"idw_float",
       [&] { skin_float.deform(rest.data(), displacement.data(), out_other.data(), threads); },
       {}},
      {"mls", [&] { mls.deform(rest.data(), displacement.data(), out_mls.data(), threads); }, {}},
      {"mls_float",
       [&] { mls_float.deform(rest.data(), displacement.data(), out_other.data(), threads); },
       {}},
  };
  if (spline)  // in the rounds too: its ratio to idw is paired as the others are
    passes.push_back(
        {"spline", [&] { spline->deform(rest.data(), displacement.data(), out_other.data(), threads); }, {}});
  std::vector<double> ratio_spline;
  std::vector<double> ratio_idw, ratio_mls;
  for (int round = 0; round < o.rounds; ++round) {
    for (Pass& pass : passes) pass.ms.push_back(medianMs(o.repetitions, pass.run));
    ratio_idw.push_back(passes[0].ms.back() / passes[1].ms.back());
    ratio_mls.push_back(passes[0].ms.back() / passes[3].ms.back());
    if (spline) ratio_spline.push_back(passes[5].ms.back() / passes[1].ms.back());
  }
  const double ms = median(passes[1].ms), plain_ms = median(passes[0].ms), mls_ms = median(passes[3].ms);

  // Streaming copy, same threads: the bandwidth bound. Source and destination of 128 MB each at least,
  // four times a large last-level cache, so the copy runs from memory as the pass does.
  const std::size_t bytes_per_vertex = skin.bytesPerVertex();
  const std::size_t copy_floats =
      std::max<std::size_t>(rest.size() * plain.bytesPerVertex() / 8, std::size_t{32} << 20);
  std::vector<float> src(copy_floats, 1.0f), dst(copy_floats, 0.0f);
  const double copy_ms = medianMs(o.repetitions, [&] {
    deform::parallelFor(copy_floats, threads, [&](std::size_t b, std::size_t e) {
      std::memcpy(dst.data() + b, src.data() + b, (e - b) * sizeof(float));
    });
  });
  const double copy_bytes_per_ms = 2.0 * static_cast<double>(copy_floats * sizeof(float)) / copy_ms;

  // Baseline: array of structs, Eigen double accumulation, same threads.
  std::vector<SkinnedVertex> aos(rest.size());
  for (std::size_t j = 0; j < rest.size(); ++j) {
    aos[j].rest_m = rest[j];
    for (std::size_t k = 0; k < skin.influences(); ++k)
      aos[j].influences.push_back({skin_float.slotIndex(j, k), skin_float.slotWeight(j, k)});
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
  // Precision against double: the float weights accumulated in double stand for the exact pass (their
  // own rounding, 6e-8 relative, is far below the fixed-point step).
  double disagreement_m = 0, mls_disagreement_m = 0;
  for (std::size_t j = 0; j < out.size(); ++j) {
    Eigen::Vector3d mls_exact = rest[j].cast<double>();
    for (std::size_t k = 0; k < mls_float.influences(); ++k)
      mls_exact += static_cast<double>(mls_float.slotWeight(j, k)) * displacement[mls_float.slotIndex(j, k)];
    Eigen::Vector3d idw_exact = rest[j].cast<double>();
    for (const Influence& inf : aos[j].influences) idw_exact += inf.weight * displacement[inf.control];
    disagreement_m = std::max(disagreement_m, (out[j].cast<double>() - idw_exact).norm());
    mls_disagreement_m = std::max(mls_disagreement_m, (out_mls[j].cast<double>() - mls_exact).norm());
  }

  const double pass_bytes_per_ms = static_cast<double>(bytes_per_vertex * rest.size()) / ms;
  const auto spread = [](const std::vector<double>& v) {
    return nlohmann::ordered_json{{"median", median(v)},
                                  {"min", *std::min_element(v.begin(), v.end())},
                                  {"max", *std::max_element(v.begin(), v.end())}};
  };
  nlohmann::ordered_json r;
  r["vertices"] = rest.size();
  r["control_points"] = control.points_m.size();
  r["k"] = skin.influences();
  r["threads"] = threads;
  r["alpha"] = o.alpha;
  r["repetitions"] = o.repetitions;
  r["rounds"] = o.rounds;
  r["ms"] = ms;
  r["vertices_per_ms"] = static_cast<double>(rest.size()) / ms;
  r["bytes_per_vertex"] = bytes_per_vertex;
  r["gb_per_s"] = pass_bytes_per_ms / 1e6;
  r["copy_gb_per_s"] = copy_bytes_per_ms / 1e6;
  r["bandwidth_fraction"] = pass_bytes_per_ms / copy_bytes_per_ms;
  r["max_error_vs_double_m"] = disagreement_m;
  r["plain"] = {{"ms", plain_ms},
                {"vertices_per_ms", static_cast<double>(rest.size()) / plain_ms},
                {"bytes_per_vertex", plain.bytesPerVertex()},
                {"bandwidth_fraction",
                 static_cast<double>(plain.bytesPerVertex() * rest.size()) / plain_ms / copy_bytes_per_ms}};
  r["speedup_vs_plain"] = spread(ratio_idw);
  r["float_layout"] = {{"ms", median(passes[2].ms)},
                       {"bytes_per_vertex", skin_float.bytesPerVertex()},
                       {"mls_ms", median(passes[4].ms)},
                       {"mls_bytes_per_vertex", mls_float.bytesPerVertex()}};
  r["baseline_aos_ms"] = aos_ms;
  r["speedup_vs_aos"] = aos_ms / ms;
  r["skin_build_ms"] = build_ms;
  r["skin_bytes"] = skin.memoryBytes();
  r["skin_reverse_index_bytes"] = skin.reverseIndexBytes();
  r["mls"] = {{"skin_build_ms", mls_build_ms},
              {"ms", mls_ms},
              {"vertices_per_ms", static_cast<double>(rest.size()) / mls_ms},
              {"bytes_per_vertex", mls.bytesPerVertex()},
              {"speedup_vs_plain", spread(ratio_mls)},
              {"max_error_vs_double_m", mls_disagreement_m},
              {"skin_bytes", mls.memoryBytes()}};
  if (spline) {
    const double spline_ms = median(passes[5].ms);
    r["spline"] = {{"skin_build_ms", spline_build_ms},
                   {"ms", spline_ms},
                   {"vertices_per_ms", static_cast<double>(rest.size()) / spline_ms},
                   {"bytes_per_vertex", spline->bytesPerVertex()},
                   {"ms_vs_idw", spread(ratio_spline)},
                   {"lattice_nodes", spline->latticeNodeCount()},
                   {"skin_bytes", spline->memoryBytes()}};
  }
  return r;
}

}  // namespace sandbox

#include <cstdio>
#include <memory>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "embed_bench.hpp"

namespace sandbox {
namespace {

struct EmbedFlags {
  EmbedBenchOptions options;
  bool json = false;
};

void runEmbed(const EmbedFlags& flags) {
  const auto r = runEmbedBench(flags.options);
  if (flags.json) {
    std::printf("%s\n", r.dump(2).c_str());
    return;
  }
  std::printf("embed: %zu vertices, %zu control points, K = %zu, %u threads, %d rounds x %d passes\n",
              r["vertices"].get<std::size_t>(), r["control_points"].get<std::size_t>(),
              r["k"].get<std::size_t>(), r["threads"].get<unsigned>(), r["rounds"].get<int>(),
              r["repetitions"].get<int>());
  const double copy = r["copy_gb_per_s"].get<double>();
  const auto& plain = r["plain"];
  std::printf("  plain kernel    %8.3f ms median (%.0f vertices/ms), %zu B/vertex = %.0f %% of copy\n",
              plain["ms"].get<double>(), plain["vertices_per_ms"].get<double>(),
              plain["bytes_per_vertex"].get<std::size_t>(),
              100.0 * plain["bandwidth_fraction"].get<double>());
  const auto ratio = [](const nlohmann::ordered_json& s) {
    std::printf("%.2fx the plain kernel (rounds %.2f-%.2f)", s["median"].get<double>(),
                s["min"].get<double>(), s["max"].get<double>());
  };
  std::printf("  deform pass     %8.3f ms median (%.0f vertices/ms), ", r["ms"].get<double>(),
              r["vertices_per_ms"].get<double>());
  ratio(r["speedup_vs_plain"]);
  std::printf("\n  traffic         %zu B/vertex, %.2f GB/s = %.0f %% of a streaming copy (%.2f GB/s)\n",
              r["bytes_per_vertex"].get<std::size_t>(), r["gb_per_s"].get<double>(),
              100.0 * r["bandwidth_fraction"].get<double>(), copy);
  std::printf("  precision       %.2e m largest difference from the double-precision pass\n",
              r["max_error_vs_double_m"].get<double>());
  const auto& fl = r["float_layout"];
  std::printf("  float weights   %8.3f ms (%zu B/vertex; mls %.3f ms, %zu B/vertex)\n",
              fl["ms"].get<double>(), fl["bytes_per_vertex"].get<std::size_t>(), fl["mls_ms"].get<double>(),
              fl["mls_bytes_per_vertex"].get<std::size_t>());
  std::printf("  AoS baseline    %8.3f ms  (%.1fx slower)\n", r["baseline_aos_ms"].get<double>(),
              r["speedup_vs_aos"].get<double>());
  std::printf("  skin build      %8.1f ms, %.1f MB (idw), reverse index %.1f MB\n",
              r["skin_build_ms"].get<double>(), static_cast<double>(r["skin_bytes"].get<std::size_t>()) / 1e6,
              static_cast<double>(r["skin_reverse_index_bytes"].get<std::size_t>()) / 1e6);
  const auto& mls = r["mls"];
  std::printf("  mls skin        %8.3f ms median (%.0f vertices/ms), %zu B/vertex, ", mls["ms"].get<double>(),
              mls["vertices_per_ms"].get<double>(), mls["bytes_per_vertex"].get<std::size_t>());
  ratio(mls["speedup_vs_plain"]);
  std::printf("\n                  %.2e m from double, build %.1f ms\n",
              mls["max_error_vs_double_m"].get<double>(), mls["skin_build_ms"].get<double>());
  if (r.contains("spline")) {
    const auto& spline = r["spline"];
    std::printf(
        "  spline skin     %8.3f ms median (%.0f vertices/ms), %zu B/vertex, %.2fx idw's time (rounds "
        "%.2f-%.2f)\n                  %zu lattice nodes, build %.1f ms, %.1f MB\n",
        spline["ms"].get<double>(), spline["vertices_per_ms"].get<double>(),
        spline["bytes_per_vertex"].get<std::size_t>(), spline["ms_vs_idw"]["median"].get<double>(),
        spline["ms_vs_idw"]["min"].get<double>(), spline["ms_vs_idw"]["max"].get<double>(),
        spline["lattice_nodes"].get<std::size_t>(), spline["skin_build_ms"].get<double>(),
        static_cast<double>(spline["skin_bytes"].get<std::size_t>()) / 1e6);
  }
}

}  // namespace

void registerBenchCommands(CLI::App& app) {
  auto* bench = app.add_subcommand("bench", "Benchmarks of the hot passes");
  bench->require_subcommand(1);

  auto flags = std::make_shared<EmbedFlags>();
  auto* embed = bench->add_subcommand("embed", "Per-frame deform pass of the render mesh (builtin:sedan)");
  embed->add_option("--vertices", flags->options.vertices, "Render-mesh vertices")->capture_default_str();
  embed->add_option("--control-points", flags->options.control_points, "Control points N")
      ->capture_default_str();
  embed->add_option("--k", flags->options.k, "Influences per vertex (0 = dense)")->capture_default_str();
  embed->add_option("--threads", flags->options.threads, "Worker threads (0 = all cores)")
      ->capture_default_str();
  embed->add_option("--alpha", flags->options.alpha, "Inverse-distance power")->capture_default_str();
  embed->add_option("--repetitions", flags->options.repetitions, "Timed passes (median reported)")
      ->capture_default_str();
  embed
      ->add_option("--rounds", flags->options.rounds,
                   "Rounds alternating the plain kernel and the project's pass")
      ->capture_default_str();
  embed->add_flag("--spline", flags->options.spline,
                  "Also time the spline skin (up to 256 control points), in the same rounds");
  embed->add_flag("--json", flags->json, "Print one JSON object");
  embed->callback([flags] { runEmbed(*flags); });

  registerBenchStepCommand(*bench);
  registerBenchMemoryCommand(*bench);
  registerBenchGridCommand(*bench);
  registerBenchCarsCommand(*bench);
  registerBenchRenderCommand(*bench);
}

}  // namespace sandbox

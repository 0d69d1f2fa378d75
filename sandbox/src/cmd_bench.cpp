#include <cstdio>
#include <memory>

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
  std::printf("embed: %zu vertices, %zu control points, K = %zu, %u threads\n",
              r["vertices"].get<std::size_t>(), r["control_points"].get<std::size_t>(),
              r["k"].get<std::size_t>(), r["threads"].get<unsigned>());
  std::printf("  deform pass     %8.3f ms median of %d  (%.0f vertices/ms)\n", r["ms"].get<double>(),
              r["repetitions"].get<int>(), r["vertices_per_ms"].get<double>());
  std::printf("  traffic         %zu B/vertex, %.2f GB/s = %.0f %% of a streaming copy (%.2f GB/s)\n",
              r["bytes_per_vertex"].get<std::size_t>(), r["gb_per_s"].get<double>(),
              100.0 * r["bandwidth_fraction"].get<double>(), r["copy_gb_per_s"].get<double>());
  std::printf("  AoS baseline    %8.3f ms  (%.1fx slower)\n", r["baseline_aos_ms"].get<double>(),
              r["speedup_vs_aos"].get<double>());
  std::printf("  skin build      %8.1f ms, %.1f MB (idw)\n", r["skin_build_ms"].get<double>(),
              static_cast<double>(r["skin_bytes"].get<std::size_t>()) / 1e6);
  const auto& mls = r["mls"];
  std::printf("  mls skin        %8.3f ms median (%.0f vertices/ms), build %.1f ms\n",
              mls["ms"].get<double>(), mls["vertices_per_ms"].get<double>(),
              mls["skin_build_ms"].get<double>());
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
  embed->add_flag("--json", flags->json, "Print one JSON object");
  embed->callback([flags] { runEmbed(*flags); });

  registerBenchStepCommand(*bench);
  registerBenchGridCommand(*bench);
  registerBenchCarsCommand(*bench);
}

}  // namespace sandbox

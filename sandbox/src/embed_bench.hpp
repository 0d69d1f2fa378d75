#pragma once
// The embedding benchmark: the per-frame deform pass of the render mesh, against the machine's
// streaming-copy bandwidth, the plain kernel (embed_plain.hpp) and the simplest array-of-structs loop,
// measured in one run.
#include <nlohmann/json.hpp>

#include <cstddef>

namespace sandbox {

struct EmbedBenchOptions {
  std::size_t vertices = 900000;    ///< render-mesh vertices of builtin:sedan
  std::size_t control_points = 60;  ///< control points N
  std::size_t k = 8;                ///< influences per vertex (0 = dense)
  unsigned threads = 0;             ///< 0 = all cores
  double alpha = 3.5;
  int repetitions = 21;  ///< timed passes per round; the median is reported
  int rounds = 5;        ///< rounds, each timing every pass once (plain kernel, project), alternated
  /// Also time the spline skin (up to 256 points) in the rounds: its build and pass, as `spline`.
  bool spline = false;
};

/// Runs the benchmark; the JSON holds `ms` (median over rounds of each round's median), `vertices_per_ms`,
/// `bytes_per_vertex`, `bandwidth_fraction`, `copy_gb_per_s`, `max_error_vs_double_m`, `plain` (the plain
/// kernel: `ms`, `bytes_per_vertex`, ...), `speedup_vs_plain` {median, min, max over the paired rounds},
/// `float_layout` (the project's pass over float weights: the layout before), `baseline_aos_ms`,
/// `skin_build_ms` and the set-up, all for the idw skin, and `mls` with the same figures for the
/// moving-least-squares skin; with `spline`, `spline` {skin_build_ms, ms, vertices_per_ms, bytes_per_vertex,
/// ms_vs_idw {median, min, max over the paired rounds}, lattice_nodes, skin_bytes}.
nlohmann::ordered_json runEmbedBench(const EmbedBenchOptions& options);

}  // namespace sandbox

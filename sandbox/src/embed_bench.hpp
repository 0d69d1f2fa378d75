#pragma once
// The embedding benchmark: the per-frame deform pass of the render mesh, against the machine's
// streaming-copy bandwidth and against the simplest array-of-structs loop, measured in one run.
#include <nlohmann/json.hpp>

#include <cstddef>

namespace sandbox {

struct EmbedBenchOptions {
  std::size_t vertices = 900000;    ///< render-mesh vertices of builtin:sedan
  std::size_t control_points = 60;  ///< control points N
  std::size_t k = 8;                ///< influences per vertex (0 = dense)
  unsigned threads = 0;             ///< 0 = all cores
  double alpha = 3.5;
  int repetitions = 21;  ///< timed passes; the median is reported
};

/// Runs the benchmark; the JSON holds `ms` (median), `vertices_per_ms`, `bytes_per_vertex`,
/// `bandwidth_fraction`, `copy_gb_per_s`, `baseline_aos_ms`, `speedup_vs_aos`, `skin_build_ms` and the
/// set-up, all for the idw skin, and `mls` {`skin_build_ms`, `ms`, `vertices_per_ms`}: the same pass over
/// moving-least-squares weights (same layout, so the same cost; only the build differs).
nlohmann::ordered_json runEmbedBench(const EmbedBenchOptions& options);

}  // namespace sandbox

#pragma once
// `sandbox sweep run` and `sandbox sweep merge`: one shard of a plan into a folder of results, and the
// folder back into the kind's tables (README, "Sweeps").
//
// The run folder: DIR/plan.jsonl (the plan, copied by the first shard; a folder holds one plan's results)
// and DIR/cases/<case>.json, one result per case (sweep_case.hpp), each written to a temporary file and
// renamed, so a result is either whole or absent. A shard skips the cases whose result is there, so a
// killed shard run again goes on where it stopped.
#include "sweep/sweep_plan.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace sandbox {

struct SweepRunOptions {
  Shard shard;
  std::string out_dir;
  bool strict = false;        ///< refuse (rather than warn about) another build or changed scene files
  bool retry_failed = false;  ///< run again the cases whose recorded result is a failure
};

/// What a shard did.
struct ShardSummary {
  std::size_t cases = 0;    ///< the shard's cases
  std::size_t skipped = 0;  ///< already done (results kept)
  std::size_t ran = 0;      ///< run now
  std::size_t failed = 0;   ///< of the shard's results, failures (run now or kept)
};

/// Runs the shard's cases of the plan at `plan_path`. Throws deform::InputError naming the file or flag
/// for a malformed plan, a folder holding another plan, or (strict) another build or a changed scene.
ShardSummary runSweepShard(const std::string& plan_path, const SweepRunOptions& options);

/// A run folder read back: its plan and every case's measure.
struct MergedSweep {
  SweepPlan plan;
  std::vector<nlohmann::json> measured;  ///< the plan's order
};

/// Reads and checks a run folder: throws deform::InputError naming the cases missing, foreign (a result
/// of another plan, or a file that is no case of it) or unreadable; throws, when results
/// record failed cases: CommandFailure, after naming each with its exit code and error on stderr.
MergedSweep gatherSweep(const std::string& dir);

/// gatherSweep, then the kind's report into `out_dir` (the files the one-process command writes).
void mergeSweep(const std::string& dir, const std::string& out_dir);

/// The kind's report from a plan and its measures (tradeoff, custom).
void writeSweepReport(const SweepPlan& plan, const std::vector<nlohmann::json>& measured,
                      const std::string& out_dir);

}  // namespace sandbox

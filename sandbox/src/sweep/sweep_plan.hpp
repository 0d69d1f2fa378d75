#pragma once
// A sweep: many independent runs of scenes (the trade-off study, the convergence study, a custom grid),
// written as a plan that any number of processes or machines can share out (README, "Sweeps").
//
// A plan file is JSON Lines: a header line, then one line per case.
//   {"sweep_plan": 1, "kind": "tradeoff", "version": "0.1.0+abc", "options": {...}, "cases": 16}
//   {"case": "0000", "scene": "wall_crash", "scene_hash": "9f...", "overrides": ["physics_hz=2000"],
//    "measure": "tradeoff", "labels": {"knob": "reference", "value": "top"}}
// `version` is the build that wrote the plan (build_version.hpp), `scene_hash` the FNV-1a hash of the
// scene file's bytes, `measure` what a run of the case records (sweep_case.hpp), `labels` what the kind's
// merge needs to place the case in its tables. `options` are the kind's own, for its merge.
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace sandbox {

/// One independent run: a scene with overrides, and what to measure.
struct SweepCase {
  std::string id;                                    ///< "0007": its place in the plan, zero-padded
  std::string scene;                                 ///< a shipped scene's name or an absolute path
  std::string scene_hash;                            ///< FNV-1a (64 bit) of the scene file, 16 hex digits
  std::vector<std::string> overrides;                ///< `--set` overrides, in order
  std::string measure;                               ///< "tradeoff" or "crash" (sweep_case.hpp)
  nlohmann::json labels = nlohmann::json::object();  ///< the kind's own fields (knob, value, ...)
};

struct SweepPlan {
  std::string kind;     ///< "tradeoff", "converge", "stress", "grid", "custom"
  std::string version;  ///< the build that wrote it
  nlohmann::json options = nlohmann::json::object();
  std::vector<SweepCase> cases;
};

/// Which of N shards to run: cases whose index is I - 1 modulo N (round robin, so costly neighbours
/// spread over shards).
struct Shard {
  int index = 1;  ///< I, 1 .. count
  int count = 1;  ///< N
  bool holds(std::size_t case_index) const {
    return static_cast<int>(case_index % static_cast<std::size_t>(count)) == index - 1;
  }
};

/// "I/N" with 1 <= I <= N. Throws deform::InputError naming --shard otherwise.
Shard parseShard(const std::string& text);

/// The plan as text: the header, then one line per case.
std::string planText(const SweepPlan& plan);

/// Parses a plan file's text. Throws deform::InputError naming `path`, the line and the field for a
/// malformed line, an unknown header version, a wrong case count, or duplicate case ids.
SweepPlan parsePlan(const std::string& text, const std::string& path);

/// Reads and parses a plan file (InputError naming it when it cannot be read).
SweepPlan readPlan(const std::string& path);

/// The 16-hex-digit FNV-1a hash of a text (plan ids, scene hashes).
std::string textHash(const std::string& text);

/// The scene as a plan stores it: a shipped scene's name as given, any other file as an absolute path.
std::string planSceneName(const std::string& name_or_path);

/// textHash of the scene file `name_or_path` resolves to (InputError naming it when unreadable).
std::string sceneFileHash(const std::string& name_or_path);

/// A new case for `plan` (its id the next index), the scene hash filled in (none for an empty scene).
SweepCase& addCase(SweepPlan& plan, const std::string& scene, std::vector<std::string> overrides,
                   const std::string& measure, nlohmann::json labels);

/// Writes `text` to `path` atomically: a temporary file named for this process beside it, then rename.
/// Throws std::runtime_error naming the path.
void writeAtomically(const std::string& path, const std::string& text);

/// The whole file as text; throws deform::InputError naming it when it cannot be read.
std::string readWholeFile(const std::string& path);

}  // namespace sandbox

#pragma once
// Running one case of a sweep plan (sweep_plan.hpp) and what its result file holds:
//   {"case": "0007", "plan_id": "...", "status": "done", "exit_code": 0, "error": "",
//    "version": "<build>", "scene_hash": "...", "seconds": 1.9, "measured": {...}}
// A case that throws is "failed", with the message and the exit code the program would have given (2 for
// bad input, 1 otherwise). The measures:
//   "crash"    the scene to its end: the car's crash metrics and the state hash (converge, custom)
//   "tradeoff" the scene frame by frame with the skin: cost per frame, crush, strain and the render mesh
//              at the end, as little-endian float32 in base64 (tradeoff/tradeoff.hpp)
//   "stress"   one stress group (labels: group, quick), every case's verdict (stress/stress_sweep.hpp)
//   "grid"     one resolution of the benchmark grid, or one Bullet crash speed (grid/grid_sweep.hpp)
#include "sweep/sweep_plan.hpp"

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace sandbox {

/// The case's measure, as the result's "measured" object. Throws what the run throws.
nlohmann::json measureCase(const SweepCase& sweep_case);

/// measureCase wrapped into a whole result (status, error, exit code, version, seconds), never throwing
/// for a failing run.
nlohmann::json runCase(const SweepCase& sweep_case, const std::string& plan_id);

/// The crash measure: the scene with the overrides played to its end.
nlohmann::json measureCrash(const std::string& scene, const std::vector<std::string>& overrides);

/// Points as base64 of their float32 coordinates (little-endian), and back. decodePoints throws
/// deform::InputError naming `what` for text that is not such base64.
std::string encodePoints(const std::vector<Eigen::Vector3f>& points);
std::vector<Eigen::Vector3f> decodePoints(const std::string& text, const std::string& what);

/// A number a case measured (`measured[name]`); throws deform::InputError naming `what` and the field
/// when it is missing or not a number (a merged file from elsewhere).
double measuredNumber(const nlohmann::json& measured, const std::string& name, const std::string& what);

}  // namespace sandbox

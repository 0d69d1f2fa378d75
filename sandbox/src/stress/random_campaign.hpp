#pragma once
// `sandbox stress --random N --seed S`: N random crash scenes (random_scenes.hpp), each played twice and
// held to the invariants of random_checks.hpp and the same state hash; a table, a CSV, and every failing
// scene written out as a scene file that reproduces it (`sandbox run FILE`).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "stress/random_scenes.hpp"

namespace sandbox {

/// What one random scene did.
struct RandomOutcome {
  std::size_t index = 0;
  RandomScene scene;
  bool passed = false;
  std::string failures;            ///< the invariants that failed, "; "-separated; empty when it passed
  double created_percent = 0;      ///< the most energy the run created, % of the energy through it
  double car_balance_percent = 0;  ///< the largest share a car's own balance left on the side of creation [%]
  double max_rise_m = 0;           ///< the highest any car's centre of mass rose above its start [m]
  std::size_t impacted = 0;        ///< cars that hit something
  double seconds = 0;              ///< wall time of both runs [s]
};

/// Plays scene `index` of `seed` twice and checks it. A scene that the reader refuses is a failure (a bug
/// of the generator), named as such.
RandomOutcome runRandomScene(uint64_t seed, std::size_t index);

/// Scenes first .. first+count-1 of `seed`, calling `on_scene` after each (for progress).
std::vector<RandomOutcome> runRandomCampaign(uint64_t seed, std::size_t first, std::size_t count,
                                             const std::function<void(const RandomOutcome&)>& on_scene = {});

/// The table's header and one outcome's row, as printed (fixed-width columns).
std::string randomTableHeader();
std::string randomTableRow(const RandomOutcome& outcome);

/// Makes the folder `out_dir`; throws deform::InputError naming --out when it cannot.
void makeRandomOutputFolder(const std::string& out_dir);
/// Writes `out_dir`/<scene name>.json when `outcome` failed (at once: a campaign stopped later keeps it).
void writeFailingScene(const RandomOutcome& outcome, const std::string& out_dir);
/// Writes `out_dir`/stress_random.csv, a row per outcome.
void writeRandomCsv(const std::vector<RandomOutcome>& outcomes, const std::string& out_dir);

}  // namespace sandbox

// `sandbox stress`: the stability table (stress/stress_suite.hpp), its sweep (stress/stress_sweep.hpp) run
// group by group and merged in this process, printed and written as CSV and Markdown. With --random N, a
// campaign of N random crash scenes instead (stress/random_campaign.hpp).
#include <deform/error.hpp>

#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "stress/random_campaign.hpp"
#include "stress/stress_sweep.hpp"

namespace sandbox {
namespace {

struct StressFlags {
  std::optional<std::string> out_dir;
  bool quick = false;
  std::vector<std::string> groups;
  std::optional<std::string> random;  ///< scenes of the random campaign, as typed
  std::optional<std::string> seed;
  std::optional<std::string> first;  ///< the first scene's index, as typed
};

void runStress(const StressFlags& flags) {
  const SweepPlan plan = planStress(flags.groups, flags.quick);
  std::vector<nlohmann::json> measured;
  for (const SweepCase& c : plan.cases)
    measured.push_back(measureStressGroup(c.labels.at("group").get<std::string>(), flags.quick));
  writeStressSweepReport(plan, measured, flags.out_dir.value_or("out/stress"));
}

// A whole number from `lowest` up, or InputError naming the flag.
uint64_t wholeNumber(const std::string& flag, const std::string& text, uint64_t lowest) {
  const bool digits =
      !text.empty() && text.size() <= 19 && text.find_first_not_of("0123456789") == std::string::npos;
  if (!digits || std::stoull(text) < lowest)
    throw deform::InputError(flag + ": must be a whole number >= " + std::to_string(lowest) + " (got '" +
                             text + "')");
  return std::stoull(text);
}

void runRandom(const StressFlags& flags) {
  if (flags.quick || !flags.groups.empty())
    throw deform::InputError("--random: runs random scenes, not the groups (drop --quick and --group)");
  const std::size_t count = wholeNumber("--random", *flags.random, 1);
  const uint64_t seed = flags.seed ? wholeNumber("--seed", *flags.seed, 0) : 1;
  const std::size_t first = flags.first ? wholeNumber("--first", *flags.first, 0) : 0;
  if (first > std::numeric_limits<std::size_t>::max() - count)
    throw deform::InputError("--first: the scenes FIRST .. FIRST+N-1 must have indices below 2^64 (got " +
                             std::to_string(first) + " and N = " + std::to_string(count) + ")");
  const std::string out_dir = flags.out_dir.value_or("out/stress_random");
  std::printf("%zu random crash scenes from scene %zu, seed %llu\n%s\n", count, first,
              static_cast<unsigned long long>(seed), randomTableHeader().c_str());
  std::fflush(stdout);
  makeRandomOutputFolder(out_dir);
  const std::vector<RandomOutcome> outcomes =
      runRandomCampaign(seed, first, count, [&](const RandomOutcome& o) {
        std::printf("%s\n", randomTableRow(o).c_str());
        std::fflush(stdout);
        writeFailingScene(o, out_dir);
      });
  writeRandomCsv(outcomes, out_dir);
  std::size_t failed = 0;
  for (const RandomOutcome& o : outcomes) failed += o.passed ? 0 : 1;
  std::printf("wrote %s/stress_random.csv%s\n", out_dir.c_str(),
              failed > 0 ? " and every failing scene as a scene file (sandbox run FILE)" : "");
  std::printf("%zu passed, %zu failed\n", count - failed, failed);
  std::fflush(stdout);
  if (failed > 0)
    throw CommandFailure(std::to_string(failed) + " of " + std::to_string(count) +
                         " random scenes broke an invariant");
}

}  // namespace

void registerStressCommand(CLI::App& app) {
  auto flags = std::make_shared<StressFlags>();
  auto* cmd =
      app.add_subcommand("stress", "Stability at the extremes: every range to its ends, with a table");
  cmd->add_option("--out", flags->out_dir,
                  "Folder for stress.csv and stress.md (default out/stress; with --random: stress_random.csv "
                  "and the failing scenes, default out/stress_random)");
  cmd->add_flag("--quick", flags->quick, "The ends of each range only (under two minutes)");
  cmd->add_option("--group", flags->groups, "Only these groups (repeatable)");
  cmd->add_option("--random", flags->random,
                  "Instead: N random crash scenes, each played twice and checked (energy not created, no "
                  "launch past the ballistic bound, finite, no tunnelling, the same hash)");
  cmd->add_option("--seed", flags->seed, "With --random: the seed (a whole number; default 1)");
  cmd->add_option("--first", flags->first,
                  "With --random: the index of the first scene (default 0): scenes FIRST .. FIRST+N-1, each "
                  "the same as in a campaign from 0 (a campaign split across machines, or one scene again)");
  cmd->callback([flags] {
    if (flags->random) {
      runRandom(*flags);
      return;
    }
    if (flags->seed) throw deform::InputError("--seed: only with --random N");
    if (flags->first) throw deform::InputError("--first: only with --random N");
    runStress(*flags);
  });
}

}  // namespace sandbox

// `sandbox bench step`: the cost of one step of the deformable body (deform/deformable_body.hpp) under
// a contact: a wall pressed 5 cm into the front of the car for every measured step.
#include <deform/body_settings.hpp>
#include <deform/control_mesh.hpp>
#include <deform/deformable_body.hpp>
#include <deform/error.hpp>
#include <deform/masses.hpp>
#include <deform/mesh_import.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <scenes/scene_run.hpp>

#include <CLI/CLI.hpp>
#include "baselines/bullet_peer.hpp"

#include "commands.hpp"
#include "step_cost.hpp"

namespace sandbox {
namespace {

/// Steps in each block of --against-one-thread (ThreadSpeedup).
constexpr std::size_t kSpeedupBlockSteps = 20;

struct BenchStepFlags {
  std::string mesh = "builtin:sedan";
  std::size_t control_points = 60;
  uint32_t substeps = 4;
  uint32_t iterations = 1;
  std::size_t steps = 200;  ///< measured steps
  std::size_t warmup = 20;  ///< steps before measuring (the wall has crushed the front by then)
  double dt_s = 1.0 / 60;
  double mass_kg = 1500;
  bool anchored_columns = false;  ///< deform::BodyDescription::anchored_columns
  bool yield_limited = false;     ///< deform::SolverParams::yield_limited
  uint32_t threads = 1;           ///< deform::SolverParams::threads
  bool narrow = false;            ///< deform::SolverParams::wide_sweep off
  std::string peer;  ///< "" or "bullet": the same body in Bullet's btSoftBody, measured after ours
  bool against_one_thread = false;  ///< also one thread against `threads`, paired in one process
  bool json = false;
};

void check(const BenchStepFlags& f) {
  if (f.control_points < 4)
    throw deform::InputError("--control-points: must be at least 4 (got " + std::to_string(f.control_points) +
                             ")");
  if (f.substeps < 1) throw deform::InputError("--substeps: must be at least 1 (got 0)");
  if (f.iterations < 1) throw deform::InputError("--iterations: must be at least 1 (got 0)");
  if (f.steps < 1) throw deform::InputError("--steps: must be at least 1 (got 0)");
  if (f.threads < 1) throw deform::InputError("--threads: must be at least 1 (got 0)");
  if (!(std::isfinite(f.dt_s) && f.dt_s > 0)) throw deform::InputError("--dt: must be finite and > 0");
  if (!(std::isfinite(f.mass_kg) && f.mass_kg > 0))
    throw deform::InputError("--mass-kg: must be finite and > 0");
  if (f.against_one_thread && f.threads < 2)
    throw deform::InputError("--against-one-thread: needs --threads 2 or more (got " +
                             std::to_string(f.threads) + ")");
  if (!f.peer.empty() && f.peer != "bullet")
    throw deform::InputError("--peer: only \"bullet\" (got \"" + f.peer + "\")");
}

/// The text form of `bench step`'s JSON object `r`.
void printBenchStep(const BenchStepFlags& f, const nlohmann::ordered_json& r) {
  const auto count = [&](const char* key) { return r[key].get<std::size_t>(); };
  const auto number = [&](const char* key) { return r[key].get<double>(); };
  std::printf("deformation step: %zu control points, %zu constraints (%zu edges, %zu spokes, %zu bends)\n",
              count("control_points"), count("constraints"), count("edges"), count("spokes"), count("bends"));
  std::printf("  %u substeps x %u iterations, dt %.6g s, wall 5 cm into the front (%zu points in contact)\n",
              f.substeps, f.iterations, f.dt_s, count("contact_points"));
  std::printf(
      "  median %.2f us per step (thread CPU time; wall %.2f us), %.2f ns per constraint per iteration "
      "(%s, %u thread%s, %zu steps); state hash %s\n",
      number("us_per_step"), number("wall_us_per_step"), number("ns_per_constraint_iteration"),
      f.threads > 1 ? "wall time" : "CPU time", f.threads, f.threads > 1 ? "s" : "", f.steps,
      r["state_hash"].get<std::string>().c_str());
  std::printf(
      "  at the end: largest deviation from rest %.3f m, %zu of %zu points within 1 mm of their cap\n",
      number("max_deviation_m"), count("points_at_cap"), count("control_points"));
  if (r.contains("peer")) {
    const auto& peer = r["peer"];
    std::printf(
        "  peer bullet: btSoftBody, %zu nodes, %zu links, no contact: %.2f us per step, %.2f ns per "
        "constraint per iteration%s\n  ratio (ours / bullet) %.2f\n",
        peer["nodes"].get<std::size_t>(), peer["links"].get<std::size_t>(), peer["us_per_step"].get<double>(),
        peer["ns_per_constraint_iteration"].get<double>(), peer["finite"].get<bool>() ? "" : " (DIVERGED)",
        peer["ratio"].get<double>());
  }
  if (r.contains("against_one_thread")) {
    const auto& a = r["against_one_thread"];
    std::printf(
        "  against one thread, in turn in blocks of %zu steps (%zu pairs, wall time): 1 thread %.2f ns, %u "
        "threads %.2f ns per constraint per iteration\n  speed-up %.2fx (quartiles %.2f-%.2f); state hash %s "
        "after the mixed steps, %s on one thread throughout (%s)\n",
        a["block_steps"].get<std::size_t>(), a["block_pairs"].get<std::size_t>(),
        a["one_thread_ns_per_constraint_iteration"].get<double>(), f.threads,
        a["ns_per_constraint_iteration"].get<double>(), a["speedup"].get<double>(),
        a["speedup_lower_quartile"].get<double>(), a["speedup_upper_quartile"].get<double>(),
        a["mixed_state_hash"].get<std::string>().c_str(),
        a["one_thread_state_hash"].get<std::string>().c_str(),
        a["same_state_hash"].get<bool>() ? "the same" : "DIFFERENT");
  }
}

void runBenchStep(const BenchStepFlags& f) {
  check(f);
  const deform::VehicleModel model = deform::loadVehicleModel(f.mesh);
  std::vector<Eigen::Vector3d> points;
  points.reserve(model.body.positions_m.size());
  for (const auto& p : model.body.positions_m) points.push_back(p.cast<double>());
  const deform::ControlMesh mesh = deform::buildControlMesh(points, f.control_points, f.mesh.c_str());
  const deform::MassSplit masses = deform::distributeMass(mesh, f.mass_kg);
  deform::BodyDescription description;
  description.anchored_columns = f.anchored_columns;
  const auto settings =
      std::make_shared<const deform::BodySettings>(deform::createBodySettings(mesh, masses, description));
  StepCostOptions options;
  options.substeps = f.substeps;
  options.iterations = f.iterations;
  options.warmup = f.warmup;
  options.steps = f.steps;
  options.dt_s = f.dt_s;
  options.yield_limited = f.yield_limited;
  options.threads = f.threads;
  options.wide_sweep = !f.narrow;
  const StepCost cost = measureStepCost(settings, options);
  const std::size_t constraints = settings->constraintCount();

  nlohmann::ordered_json r;
  r["mesh"] = f.mesh;
  r["control_points"] = settings->pointCount();
  r["constraints"] = constraints;
  r["edges"] = settings->edges.size();
  r["spokes"] = settings->spokes.size();
  r["bends"] = settings->bends.size();
  r["substeps"] = f.substeps;
  r["iterations"] = f.iterations;
  r["anchored_columns"] = f.anchored_columns;
  r["yield_limited"] = f.yield_limited;
  r["threads"] = f.threads;
  r["wide_sweep"] = !f.narrow;
  r["dt_s"] = f.dt_s;
  r["steps"] = f.steps;
  r["contact_points"] = cost.contact_points;
  r["us_per_step"] = cost.us_per_step;
  r["wall_us_per_step"] = cost.wall_us_per_step;
  r["ns_per_constraint_iteration"] = cost.ns_per_constraint_iteration;
  r["max_deviation_m"] = cost.max_deviation_m;
  r["points_at_cap"] = cost.points_at_cap;
  r["state_hash"] = scenes::hashHex(cost.state_hash);
  if (f.peer == "bullet") {
    const baselines::PeerStepCost peer = baselines::bulletPeerStepCost(
        *settings, f.mass_kg, f.substeps, f.iterations, f.warmup, f.steps, f.dt_s);
    r["peer"] = {{"name", "bullet"},
                 {"nodes", peer.nodes},
                 {"links", peer.links},
                 {"us_per_step", peer.us_per_step},
                 {"ns_per_constraint_iteration", peer.ns_per_constraint_iteration},
                 {"finite", peer.finite},
                 {"ratio", cost.ns_per_constraint_iteration / peer.ns_per_constraint_iteration}};
  }
  ThreadSpeedup speedup;
  if (f.against_one_thread) {
    speedup = measureThreadSpeedup(settings, options, kSpeedupBlockSteps);
    const double per_ns = 1e3 / (static_cast<double>(constraints) * f.substeps * f.iterations);
    r["against_one_thread"] = {
        {"one_thread_ns_per_constraint_iteration", speedup.one_thread_wall_us * per_ns},
        {"ns_per_constraint_iteration", speedup.many_threads_wall_us * per_ns},
        {"speedup", speedup.speedup},
        {"speedup_lower_quartile", speedup.speedup_low},
        {"speedup_upper_quartile", speedup.speedup_high},
        {"block_steps", kSpeedupBlockSteps},
        {"block_pairs", speedup.pairs},
        {"one_thread_state_hash", scenes::hashHex(speedup.one_thread_hash)},
        {"mixed_state_hash", scenes::hashHex(speedup.mixed_hash)},
        {"same_state_hash", speedup.one_thread_hash == speedup.mixed_hash}};
  }
  const bool hashes_differ = f.against_one_thread && speedup.one_thread_hash != speedup.mixed_hash;
  if (f.json)
    std::printf("%s\n", r.dump(2).c_str());
  else
    printBenchStep(f, r);
  if (hashes_differ)
    throw CommandFailure("bench step: the state differs between 1 and " + std::to_string(f.threads) +
                         " threads");
}
}  // namespace

void registerBenchStepCommand(CLI::App& bench) {
  auto flags = std::make_shared<BenchStepFlags>();
  auto* step = bench.add_subcommand("step", "Median cost of one step of the deformable body under a contact");
  step->add_option("--mesh", flags->mesh,
                   "builtin:sedan[?vertices=N], builtin:can, builtin:box or a mesh file")
      ->capture_default_str();
  step->add_option("--control-points", flags->control_points, "Control points N (level of detail)")
      ->capture_default_str();
  step->add_option("--substeps", flags->substeps, "Substeps per step")->capture_default_str();
  step->add_option("--iterations", flags->iterations, "Gauss-Seidel iterations per substep")
      ->capture_default_str();
  step->add_option("--steps", flags->steps, "Measured steps")->capture_default_str();
  step->add_option("--warmup", flags->warmup, "Steps before measuring")->capture_default_str();
  step->add_option("--dt", flags->dt_s, "Time step [s]")->capture_default_str();
  step->add_option("--mass-kg", flags->mass_kg, "Vehicle mass [kg]")->capture_default_str();
  step->add_flag("--anchored-columns", flags->anchored_columns,
                 "Crush columns held at a rest place (scene key anchored_columns)");
  step->add_flag("--yield-limited", flags->yield_limited,
                 "Force-limited constraints (scene key yield_limited)");
  step->add_option("--threads", flags->threads,
                   "Threads sweeping the body (deform SolverParams::threads: 1, or 2 for its halves)")
      ->capture_default_str();
  step->add_option("--peer", flags->peer, "Also run the same body in a peer engine: bullet (btSoftBody)");
  step->add_flag(
      "--against-one-thread", flags->against_one_thread,
      "With --threads 2: also step the body on one thread and on --threads in turn, in blocks of " +
          std::to_string(kSpeedupBlockSteps) +
          " steps in this process, and print the speed-up (median of the blocks' ratios) and both state "
          "hashes");
  step->add_flag("--narrow", flags->narrow,
                 "One constraint and point at a time (deform SolverParams::wide_sweep off; the same bits)");
  step->add_flag("--json", flags->json, "Print one JSON object");
  step->callback([flags] { runBenchStep(*flags); });
}

}  // namespace sandbox

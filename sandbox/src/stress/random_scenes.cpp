#include "stress/random_scenes.hpp"

#include "stress/stress_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "stress/random_obstacles.hpp"

namespace sandbox {
namespace {

using stress_support::kDegree;

using nlohmann::json;

// The built-in sedan's footprint about its vehicle origin (deform/io/builtin_sedan.cpp: 4.8 m long, body
// 1.8 m wide), a few centimetres grown [m].
const Eigen::Vector2d kCarHalfSize_m(2.45, 0.95);
// Everything placed stays this far from every car at the start (the reader allows 1 cm of overlap) [m].
constexpr double kClearance_m = 0.1;
// Cars aimed at their own obstacles start this far apart across the world's Y, so that their crashes do
// not meet before they happen [m].
constexpr double kRegionSpacing_m = 40;
// A car slower than this is driven into its obstacle by the throttle; its acceleration at full throttle
// taken a little low (the sedan at any mass: 3.9 m/s^2 from rest, 1.5 at 0.4), so that the scene lasts
// until it arrives [m/s], [m/s^2].
constexpr double kSlowestCar_mps = 10 / 3.6;
constexpr double kAccelerationAtFullThrottle_mps2 = 3.0;
// The scene runs this long after the last car reaches its target [s].
constexpr double kAfterImpact_s = 0.7;
// A car is aimed at "nothing": it is only struck by another.
constexpr int kOwnObstacle = -1, kStruckOnly = -2;

const char* const kPresets[] = {"fast", "balanced", "accurate", "fine", "finest"};
constexpr std::size_t kBalanced = 1, kAccurate = 2;
// A car's step at each preset against a balanced car's: the wall crash at 500 Hz on one core here took
// 0.04, 0.075, 0.15, 0.23 and 0.49 ms a step. From 250 points a step in contact takes substeps of at most
// 0.5 ms (scenes/README.md, longest_contact_substep_s): below 500 Hz, more of them.
constexpr double kPresetCost[] = {0.5, 1, 2, 3, 6.5};
// A car that meets another is solved with it as one, and its contacts are searched on both bodies: three
// balanced cars meeting at 80-200 km/h took 0.76 ms a car and step here; from 250 points twice that again
// (three cars meeting at 99 Hz, two of them accurate, took 250 ms a step).
constexpr double kCarToCarCost = 6;
// A scene's cost in balanced car-steps at most: about 0.6 s a run on one core here (0.075 ms each), for a
// crash that stays physical (one that creates energy can take far longer).
constexpr double kBudgetCarSteps = 8000;

struct CarDraw {
  Eigen::Vector2d position_m{0, 0};
  double heading_deg = 0;
  double speed_kmh = 0;
  double mass_kg = 1500;
  std::size_t preset = 1;  ///< into kPresets
  bool visual = false;
  int aim = kOwnObstacle;     ///< kOwnObstacle, kStruckOnly or the index of the car it is aimed at
  std::string target;         ///< the table's word for what it is aimed at
  double reach_s = 0;         ///< when it reaches its target [s]
  double start_throttle = 0;  ///< > 0: a slow car driven from t = 0 [-]
  json drive_keys = json::array();

  Eigen::Vector2d direction() const { return headingVector(heading_deg * kDegree); }
  Eigen::Vector2d left() const { return {-direction().y(), direction().x()}; }
  double speed_mps() const { return speed_kmh / 3.6; }
  Footprint footprint() const { return {position_m, heading_deg * kDegree, kCarHalfSize_m}; }
};

Eigen::Vector2d roundedPosition(const Eigen::Vector2d& p_m) {
  return {RandomDraws::rounded(p_m.x(), 1e-3), RandomDraws::rounded(p_m.y(), 1e-3)};
}

// How many cars and which each is aimed at: its own obstacle, an earlier car, or nothing (a car that is
// only struck).
std::vector<int> drawAims(RandomDraws& draws) {
  const std::size_t cars = 1 + draws.weighted({45, 35, 20});
  std::vector<int> aims(cars, kOwnObstacle);
  if (cars == 1) return aims;
  aims[0] = draws.chance(0.7) ? kOwnObstacle : kStruckOnly;
  aims[1] = aims[0] == kStruckOnly || draws.chance(0.6) ? 0 : kOwnObstacle;
  if (cars == 3) aims[2] = draws.chance(0.5) ? static_cast<int>(draws.below(2)) : kOwnObstacle;
  return aims;
}

// A car aimed at its own obstacle, in its own region of the world; the obstacle in its path, its near side
// a gap ahead of the car's front and offset across the path by less than the two overlap. The car reaches
// it after the travel that brings their footprints together (an oblique wall's face may be further in
// the car's lane than its nearest corner).
void placeAtObstacle(RandomDraws& draws, CarDraw& car, std::size_t region, std::vector<Footprint>& placed,
                     json& obstacles) {
  car.position_m =
      roundedPosition({draws.uniform(-3, 3, 1e-3),
                       static_cast<double>(region) * kRegionSpacing_m + draws.uniform(-3, 3, 1e-3)});
  placed.push_back(car.footprint());
  const bool slow = car.speed_mps() < kSlowestCar_mps;
  if (slow) car.start_throttle = draws.uniform(0.4, 1, 0.01);
  const double farthest_gap_m = slow ? 1.2 : std::min(8.0, 0.6 * car.speed_mps());
  const ObstacleShape shape = drawObstacleShape(draws);
  const double yaw_deg = RandomDraws::rounded(car.heading_deg + shape.yaw_to_path_deg, 0.1);
  const Footprint turned = obstacleFootprint(shape, {0, 0}, shape.yaw_to_path_deg);
  const double across_m = halfExtentAlong_m(turned, {0, 1}) + kCarHalfSize_m.y();
  const double along_m = halfExtentAlong_m(turned, {1, 0});
  double travel_m = -1;
  json object;
  Footprint footprint;
  for (int attempt = 0; attempt < 20 && (travel_m < 0 || travel_m > farthest_gap_m + 1); ++attempt) {
    const double offset_m = draws.uniform(-0.85, 0.85, 1e-3) * across_m;
    // Further along the path until it stands clear of every car (an oblique wall's corner may not be).
    for (double gap_m = draws.uniform(0.2, farthest_gap_m, 0.01);; gap_m += 0.25) {
      Eigen::Vector2d centre_m =
          car.position_m + car.direction() * (kCarHalfSize_m.x() + gap_m + along_m) + car.left() * offset_m;
      object = placeObstacle(shape, centre_m, yaw_deg);
      footprint = obstacleFootprint(shape, centre_m, yaw_deg);
      if (gapToAll_m(footprint, placed) >= kClearance_m) break;
    }
    travel_m = travelToContact_m(car.footprint(), car.direction(), footprint, 50);
  }
  placed.push_back(footprint);
  obstacles.push_back(object);
  car.target = shape.label;
  travel_m = std::max(travel_m, 0.0);
  const double v_mps = car.speed_mps();
  const double a_mps2 = kAccelerationAtFullThrottle_mps2 * car.start_throttle;
  car.reach_s =
      slow ? (-v_mps + std::sqrt(v_mps * v_mps + 2 * a_mps2 * travel_m)) / a_mps2 : travel_m / v_mps;
}

// A car aimed at car `other`: where `other` will be after T s, reached from any angle at any speed within
// T, and the car's start clear of everything. False when no draw fits.
bool placeAtCar(RandomDraws& draws, CarDraw& car, const CarDraw& other, std::vector<Footprint>& placed) {
  for (int attempt = 0; attempt < 40; ++attempt) {
    const double meet_s = other.aim == kOwnObstacle
                              ? std::max(0.1, draws.uniform(0.15, 0.9, 1e-3) * other.reach_s)
                              : draws.uniform(0.15, 0.6, 1e-3);
    car.heading_deg = RandomDraws::rounded(other.heading_deg + draws.uniform(-180, 180, 0.1), 0.1);
    if (car.heading_deg > 360) car.heading_deg -= 360;
    if (car.heading_deg < -360) car.heading_deg += 360;
    car.speed_kmh = draws.uniform(15, 250, 0.1);
    const Eigen::Vector2d meet_m = other.position_m + other.direction() * other.speed_mps() * meet_s;
    const double offset_m = draws.uniform(-1.5, 1.5, 1e-3);
    car.position_m =
        roundedPosition(meet_m + car.left() * offset_m - car.direction() * car.speed_mps() * meet_s);
    if (gapToAll_m(car.footprint(), placed) < kClearance_m) continue;
    placed.push_back(car.footprint());
    car.reach_s = meet_s;
    car.target = "car" + std::to_string(car.aim);
    return true;
  }
  return false;
}

// Pedals and steering at random times: before the car reaches its target only what keeps it on its way
// (throttle, a little steering), after it anything the schema allows.
void drawDriveKeys(RandomDraws& draws, CarDraw& car, double duration_s) {
  std::vector<json> keys;
  if (car.start_throttle > 0) keys.push_back({{"t_s", 0.0}, {"throttle", car.start_throttle}});
  const std::size_t count = draws.weighted({40, 30, 20, 10});
  for (std::size_t i = 0; i < count; ++i) {
    json key = {{"t_s", draws.uniform(0, duration_s, 0.01)}};
    if (key["t_s"].get<double>() < car.reach_s) {
      if (car.start_throttle > 0)
        key["throttle"] = car.start_throttle;
      else if (draws.chance(0.5))
        key["throttle"] = draws.uniform(0, 1, 0.01);
      if (draws.chance(0.3)) key["steering"] = draws.uniform(-0.15, 0.15, 0.01);
    } else if (draws.chance(0.1)) {
      key["target_speed_kmh"] = draws.uniform(0, 100, 0.1);
    } else {
      if (draws.chance(0.5)) key["brake"] = draws.uniform(0, 1, 0.01);
      if (draws.chance(0.3)) key["throttle"] = draws.uniform(0, 1, 0.01);
      if (draws.chance(0.4)) key["steering"] = draws.uniform(-1, 1, 0.01);
      if (draws.chance(0.15)) key["handbrake"] = true;
    }
    keys.push_back(key);
  }
  std::stable_sort(keys.begin(), keys.end(), [](const json& a, const json& b) {
    return a["t_s"].get<double>() < b["t_s"].get<double>();
  });
  car.drive_keys = keys;
}

json carObject(const CarDraw& car, std::size_t index) {
  json object = {{"name", "car" + std::to_string(index)},
                 {"mesh", "builtin:sedan?vertices=1000"},
                 {"mass_kg", car.mass_kg},
                 {"coupling", car.visual ? "visual" : "crush"},
                 {"start",
                  {{"position_m", {car.position_m.x(), car.position_m.y()}},
                   {"heading_deg", car.heading_deg},
                   {"speed_kmh", car.speed_kmh}}},
                 {"deformation", {{"preset", kPresets[car.preset]}}}};
  if (!car.drive_keys.empty()) object["drive"] = {{"keys", car.drive_keys}};
  return object;
}

double internalRate_hz(double physics_hz) {
  return physics_hz < 120 ? physics_hz * std::ceil(120 / physics_hz) : physics_hz;
}

double costCarSteps(const std::vector<CarDraw>& cars, double physics_hz, double duration_s) {
  const double rate_hz = internalRate_hz(physics_hz);
  double per_step = 0;
  for (std::size_t i = 0; i < cars.size(); ++i) {
    bool meets_car = cars[i].aim >= 0;
    for (const CarDraw& other : cars) meets_car = meets_car || other.aim == static_cast<int>(i);
    const bool fine = cars[i].preset >= kAccurate;
    per_step += kPresetCost[cars[i].preset] * (fine ? std::max(1.0, 500 / rate_hz) : 1) *
                (meets_car ? kCarToCarCost * (fine ? 2 : 1) : 1);
  }
  return per_step * rate_hz * duration_s;
}

// Within the budget: the costliest car's preset down to balanced first, then the rate down (not below 120
// Hz), then balanced cars down to fast.
void fitBudget(std::vector<CarDraw>& cars, double& physics_hz, double duration_s) {
  while (costCarSteps(cars, physics_hz, duration_s) > kBudgetCarSteps) {
    CarDraw& costliest = *std::max_element(
        cars.begin(), cars.end(), [](const CarDraw& a, const CarDraw& b) { return a.preset < b.preset; });
    if (costliest.preset > kBalanced) {
      --costliest.preset;
    } else if (physics_hz > 120) {
      physics_hz = std::max(120.0, std::round(physics_hz * 0.7));
    } else if (costliest.preset > 0) {
      --costliest.preset;
    } else {
      return;
    }
  }
}

std::string joined(const std::vector<CarDraw>& cars, const auto& part) {
  std::string text;
  for (const CarDraw& car : cars) text += (text.empty() ? "" : "/") + part(car);
  return text;
}

RandomSceneOutline outlineOf(const std::vector<CarDraw>& cars, double physics_hz) {
  RandomSceneOutline o;
  o.cars = cars.size();
  o.speeds_kmh = joined(cars, [](const CarDraw& c) {
    char text[16];
    std::snprintf(text, sizeof text, "%.0f", c.speed_kmh);
    return std::string(text);
  });
  o.targets = joined(cars, [](const CarDraw& c) { return c.target; });
  o.physics_hz = physics_hz;
  o.presets = joined(cars, [](const CarDraw& c) { return std::string(kPresets[c.preset]); });
  o.couplings = joined(cars, [](const CarDraw& c) { return std::string(c.visual ? "visual" : "crush"); });
  return o;
}

}  // namespace

std::string randomSceneName(uint64_t seed, std::size_t index) {
  return "random_" + std::to_string(seed) + "_" + std::to_string(index);
}

RandomScene randomScene(uint64_t seed, std::size_t index) {
  RandomDraws draws(seed, index);
  double physics_hz = draws.logUniform(60, 2000, 1);
  std::vector<CarDraw> cars;
  std::vector<Footprint> placed;
  json obstacles = json::array();
  for (const int aim : drawAims(draws)) {
    CarDraw car;
    car.aim = aim;
    car.mass_kg = draws.logUniform(800, 6000, 10);
    car.preset = draws.weighted({30, 30, 25, 10, 5});
    car.visual = draws.chance(0.3);
    if (aim >= 0 && placeAtCar(draws, car, cars[static_cast<std::size_t>(aim)], placed)) {
      cars.push_back(car);
      continue;
    }
    car.aim = aim == kStruckOnly ? kStruckOnly : kOwnObstacle;
    car.heading_deg = draws.uniform(-180, 180, 0.1);
    car.speed_kmh = draws.chance(0.08) ? 0.0 : draws.uniform(0, 250, 0.1);
    if (car.aim == kOwnObstacle) {
      placeAtObstacle(draws, car, cars.size(), placed, obstacles);
    } else {
      car.position_m = roundedPosition({draws.uniform(-3, 3, 1e-3), draws.uniform(-3, 3, 1e-3)});
      placed.push_back(car.footprint());
      car.target = "-";
    }
    cars.push_back(car);
  }
  double last_reach_s = 0;
  for (const CarDraw& car : cars) last_reach_s = std::max(last_reach_s, car.reach_s);
  const double duration_s = std::ceil((last_reach_s + kAfterImpact_s) * 100) / 100;
  for (CarDraw& car : cars) drawDriveKeys(draws, car, duration_s);
  fitBudget(cars, physics_hz, duration_s);

  RandomScene scene;
  scene.name = randomSceneName(seed, index);
  scene.document = {{"name", scene.name},
                    {"description", "sandbox stress --random: scene " + std::to_string(index) + " of seed " +
                                        std::to_string(seed)},
                    {"duration_s", duration_s},
                    {"physics_hz", physics_hz},
                    {"threads", 1},
                    {"obstacles", obstacles}};
  if (cars.size() == 1) {
    scene.document["vehicle"] = carObject(cars[0], 0);
  } else {
    for (std::size_t i = 0; i < cars.size(); ++i) scene.document["vehicles"].push_back(carObject(cars[i], i));
  }
  scene.outline = outlineOf(cars, physics_hz);
  return scene;
}

}  // namespace sandbox

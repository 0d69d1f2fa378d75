// sweep: shards partition a plan, plans and points survive their text form, bad plans are refused by line
// and field, the custom grid is every combination.
#include <sweep/custom_sweep.hpp>
#include <sweep/sweep_case.hpp>
#include <sweep/sweep_plan.hpp>

#include <deform/error.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <set>

namespace {

sandbox::SweepPlan twoCasePlan() {
  sandbox::SweepPlan plan;
  plan.kind = "custom";
  plan.version = "0.1.0+test";
  plan.options = {{"keys", {"physics_hz"}}};
  for (int i = 0; i < 2; ++i) {
    sandbox::SweepCase c;
    c.id = "000" + std::to_string(i);
    c.scene = "wall_crash";
    c.scene_hash = "0123456789abcdef";
    c.overrides = {"physics_hz=" + std::to_string(500 * (i + 1)), "duration_s=0.3"};
    c.measure = "crash";
    c.labels = {{"values", {{"physics_hz", std::to_string(500 * (i + 1))}}}};
    plan.cases.push_back(c);
  }
  return plan;
}

std::string refusal(const std::string& text) {
  try {
    sandbox::parsePlan(text, "p.jsonl");
  } catch (const deform::InputError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST_CASE("sweep: every case belongs to exactly one shard of N", "[sweep]") {
  for (int n = 1; n <= 5; ++n) {
    for (std::size_t i = 0; i < 23; ++i) {
      int owners = 0;
      for (int k = 1; k <= n; ++k) owners += sandbox::Shard{k, n}.holds(i) ? 1 : 0;
      CHECK(owners == 1);
    }
  }
  const sandbox::Shard shard = sandbox::parseShard("2/4");
  CHECK(shard.index == 2);
  CHECK(shard.count == 4);
  CHECK(shard.holds(1));
  CHECK(shard.holds(5));
  CHECK_FALSE(shard.holds(2));
}

TEST_CASE("sweep: shard specs out of range or not numbers are refused naming --shard", "[sweep]") {
  for (const char* bad : {"3/2", "0/2", "1/0", "2", "a/b", "1/2x", "-1/2", "/2"}) {
    INFO(bad);
    CHECK_THROWS_WITH(sandbox::parseShard(bad), Catch::Contains("--shard") && Catch::Contains(bad));
  }
}

TEST_CASE("sweep: a plan survives its text form, and the text is stable", "[sweep]") {
  const sandbox::SweepPlan plan = twoCasePlan();
  const std::string text = sandbox::planText(plan);
  const sandbox::SweepPlan back = sandbox::parsePlan(text, "p.jsonl");
  REQUIRE(back.cases.size() == 2);
  CHECK(back.kind == "custom");
  CHECK(back.version == plan.version);
  CHECK(back.options == plan.options);
  CHECK(back.cases[1].overrides == plan.cases[1].overrides);
  CHECK(back.cases[1].labels == plan.cases[1].labels);
  CHECK(sandbox::planText(back) == text);
  CHECK(sandbox::textHash(text) != sandbox::textHash(text + " "));
}

TEST_CASE("sweep: malformed plans are refused naming the file, line and field", "[sweep]") {
  const std::string text = sandbox::planText(twoCasePlan());
  const std::string header = text.substr(0, text.find('\n') + 1);
  std::string line2 = text.substr(header.size());
  line2 = line2.substr(0, line2.find('\n') + 1);
  CHECK_THAT(refusal(""), Catch::Contains("p.jsonl: empty"));
  CHECK_THAT(refusal("{\"kind\": \"custom\"}\n"), Catch::Contains("p.jsonl:1: field 'sweep_plan'"));
  CHECK_THAT(refusal(header + "{not json\n"), Catch::Contains("p.jsonl:2: not a JSON line"));
  std::string no_overrides = line2;
  no_overrides.replace(no_overrides.find("\"overrides\""), 11, "\"overridez\"");
  CHECK_THAT(refusal(header + no_overrides), Catch::Contains("p.jsonl:2: field 'overrides'"));
  std::string bad_measure = line2;
  bad_measure.replace(bad_measure.find("\"crash\""), 7, "\"crush\"");
  CHECK_THAT(refusal(header + bad_measure), Catch::Contains("p.jsonl:2: field 'measure'"));
  CHECK_THAT(refusal(header + line2 + line2), Catch::Contains("p.jsonl:3: field 'case': '0000' twice"));
  CHECK_THAT(refusal(header + line2), Catch::Contains("header says 2 cases, the file has 1"));
}

TEST_CASE("sweep: points go through base64 bit for bit", "[sweep]") {
  for (std::size_t n : {0u, 1u, 2u, 7u}) {
    std::vector<Eigen::Vector3f> points;
    for (std::size_t i = 0; i < n; ++i)
      points.emplace_back(static_cast<float>(i) * 0.1f + 1e-7f, -std::numeric_limits<float>::denorm_min(),
                          std::nextafter(3.0f, 4.0f));
    const std::string text = sandbox::encodePoints(points);
    CHECK(text.size() == (12 * n + 2) / 3 * 4);
    const auto back = sandbox::decodePoints(text, "test");
    REQUIRE(back.size() == n);
    for (std::size_t i = 0; i < n; ++i) CHECK((back[i].array() == points[i].array()).all());
  }
  CHECK_THROWS_WITH(sandbox::decodePoints("abc", "measured.render_mesh_m"),
                    Catch::Contains("measured.render_mesh_m"));
  CHECK_THROWS_AS(sandbox::decodePoints("ab$d", "x"), deform::InputError);
}

TEST_CASE("sweep: a custom plan is every combination of the varied keys, each checked", "[sweep]") {
  sandbox::CustomSweepOptions options;
  options.scenes = {"wall_crash"};
  options.vary = {"vehicle.start.speed_kmh=20,40,56", "vehicle.deformation.control_points=30,60"};
  options.sets = {"duration_s=0.3"};
  const sandbox::SweepPlan plan = sandbox::planCustom(options);
  REQUIRE(plan.cases.size() == 6);
  std::set<std::string> combinations;
  for (const auto& c : plan.cases) {
    CHECK(c.overrides.front() == "duration_s=0.3");
    CHECK(c.scene_hash == sandbox::sceneFileHash("wall_crash"));
    combinations.insert(c.overrides[1] + " " + c.overrides[2]);
  }
  CHECK(combinations.size() == 6);
  CHECK(plan.cases[1].overrides[2] == "vehicle.deformation.control_points=60");  // the last key fastest
  CHECK(plan.cases[2].overrides[1] == "vehicle.start.speed_kmh=40");
  options.vary = {"vehicle.start.sped_kmh=20,40"};
  CHECK_THROWS_WITH(sandbox::planCustom(options), Catch::Contains("vehicle.start.sped_kmh"));
  options.vary = {"vehicle.start.speed_kmh=20,,40"};
  CHECK_THROWS_WITH(sandbox::planCustom(options), Catch::Contains("--vary"));
}

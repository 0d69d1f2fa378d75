// `sandbox bench render`: every stage timed, the total their sum, the frames written where asked.
#include <catch2/catch.hpp>

#include <deform/error.hpp>

#include <filesystem>
#include <string>

#include "bench_render.hpp"
#include "render_test_support.hpp"

namespace fs = std::filesystem;

TEST_CASE("bench render times render, readback and encode per frame and writes the frames",
          "[render][bench]") {
  const fs::path dir = render_test::scratchDir("bench_render");
  sandbox::RenderBenchOptions options;
  options.sets = {"duration_s=0.05"};  // two frames of the approach: physics is not what is measured
  options.frames = 2;
  options.width = 96;
  options.height = 54;
  options.encode = "png";
  options.out_dir = dir.string();
  const nlohmann::ordered_json r = sandbox::runRenderBench(options);

  CHECK(r["scene"] == "wall_crash");
  CHECK(r["frames"] == 2);
  CHECK(r["width"] == 96);
  const auto& ms = r["ms_per_frame"];
  double sum = 0;
  for (const char* stage : {"render", "readback", "encode"}) {
    INFO(stage);
    REQUIRE(ms.contains(stage));
    CHECK(ms[stage].get<double>() >= 0.0);
    sum += ms[stage].get<double>();
  }
  CHECK(ms["total"].get<double>() == Approx(sum));
  CHECK(ms["render"].get<double>() > 0.0);
  CHECK(fs::exists(dir / "frames" / "00000.png"));
  CHECK(fs::exists(dir / "frames" / "00001.png"));

  const std::string text = sandbox::renderBenchText(r);
  CHECK_THAT(text, Catch::StartsWith("render bench: wall_crash, 96x54, 2 frames (+1 warm-up), encode png\n"));
  for (const char* stage : {"\n  render ", "\n  readback ", "\n  encode ", "\n  total "})
    CHECK_THAT(text, Catch::Contains(stage));
  fs::remove_all(dir);
}

TEST_CASE("bench render refuses options it cannot measure", "[render][bench]") {
  sandbox::RenderBenchOptions options;
  options.encode = "gif";
  CHECK_THROWS_AS(sandbox::runRenderBench(options), deform::InputError);
  options = {};
  options.frames = 0;
  CHECK_THROWS_AS(sandbox::runRenderBench(options), deform::InputError);
}

// `sandbox mesh render` end to end: a PNG of the requested size, and bad input refused naming the flag.
#include <catch2/catch.hpp>

#include <deform/error.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "render/png_io.hpp"
#include "render_test_support.hpp"

namespace fs = std::filesystem;

namespace {

void runSandbox(std::vector<std::string> args) {
  CLI::App app{"sandbox"};
  sandbox::registerMeshCommands(app);
  std::reverse(args.begin(), args.end());  // CLI11 takes the arguments last-first
  app.parse(args);
}

}  // namespace

TEST_CASE("sandbox mesh render writes a PNG of the requested size", "[render]") {
  const fs::path dir = render_test::scratchDir("render_command_test");
  const std::string out = (dir / "box.png").string();
  runSandbox(
      {"mesh", "render", "builtin:box", "--out", out, "--width", "160", "--height", "90", "--camera", "top"});
  const sandbox::render::Image image = sandbox::render::readPng(out);
  CHECK(image.width == 160);
  CHECK(image.height == 90);

  const std::string heat = (dir / "heat.png").string();
  runSandbox({"mesh", "render", "builtin:sedan?vertices=3000", "--out", heat, "--width", "96", "--height",
              "64", "--heatmap-point", "3", "--control-points", "20"});
  CHECK(fs::exists(heat));
  fs::remove_all(dir);
}

TEST_CASE("sandbox mesh render refuses bad input naming the flag or file", "[render]") {
  const fs::path dir = render_test::scratchDir("render_command_bad");
  const std::string out = (dir / "x.png").string();
  CHECK_THROWS_WITH(runSandbox({"mesh", "render", "builtin:box", "--out", out, "--camera", "fisheye"}),
                    Catch::Contains("--camera"));
  CHECK_THROWS_WITH(runSandbox({"mesh", "render", "builtin:box", "--out", out, "--width", "0"}),
                    Catch::Contains("--width"));
  CHECK_THROWS_WITH(runSandbox({"mesh", "render", "builtin:box", "--out", "/no/such/folder/x.png"}),
                    Catch::Contains("--out"));
  CHECK_THROWS_WITH(runSandbox({"mesh", "render", "builtin:box", "--out", dir.string()}),
                    Catch::Contains("--out"));
  CHECK_THROWS_WITH(runSandbox({"mesh", "render", (dir / "missing.obj").string(), "--out", out}),
                    Catch::Contains("missing.obj"));
  CHECK_THROWS_WITH(runSandbox({"mesh", "render", "builtin:box", "--out", out, "--heatmap-point", "100000",
                                "--control-points", "8", "--width", "32", "--height", "32"}),
                    Catch::Contains("--heatmap-point"));
  CHECK_THROWS_AS(runSandbox({"mesh", "render", "builtin:box", "--out", out, "--camera", "fisheye"}),
                  deform::InputError);
  CHECK_FALSE(fs::exists(out));
  fs::remove_all(dir);
}

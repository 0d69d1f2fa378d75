// readContained (deform/io/contained_read.hpp): a read that crashes, hangs or throws in its child process
// comes back as a refusal or as its own exception, and a good one as the mesh it made, bit for bit.
#include <deform/error.hpp>

#include <catch2/catch.hpp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <stdexcept>

#include "contained_read.hpp"

using deform::ImportReport;
using deform::Mesh;

namespace {

std::string refusalOf(const std::function<Mesh(ImportReport&)>& read, int cpu_limit_s = 5) {
  ImportReport report;
  try {
    deform::readContained("car.ply", read, report, cpu_limit_s);
  } catch (const deform::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("a contained read returns its mesh and report, bit for bit", "[import]") {
  Mesh made;
  for (int i = 0; i < 1000; ++i) {
    const auto f = static_cast<float>(i);
    made.positions_m.emplace_back(0.1f * f, -1.0f / (f + 1), 3.0f);
  }
  for (std::uint32_t i = 0; i + 2 < 1000; ++i) made.triangles.push_back({i, i + 1, i + 2});
  ImportReport report;
  report.format = "PLY";
  const Mesh got = deform::readContained(
      "car.ply",
      [&](ImportReport& r) {
        r.up = deform::Axis::PosY;
        r.file_unit_m = 0.0254;
        r.mesh_instances = 7;
        return made;
      },
      report, 5);
  REQUIRE(got.positions_m.size() == made.positions_m.size());
  CHECK(std::memcmp(got.positions_m.data(), made.positions_m.data(), made.positions_m.size() * 12) == 0);
  CHECK(got.triangles == made.triangles);
  CHECK(got.normals.empty());
  CHECK(report.format == "PLY");
  CHECK(report.up == deform::Axis::PosY);
  CHECK(report.file_unit_m == 0.0254);
  CHECK(report.mesh_instances == 7);
}

TEST_CASE("a contained read that crashes, hangs or refuses is refused naming the file", "[import]") {
  // An abort inside the dependency (assimp's assertions), with its last line in the one message.
  const std::string aborted = refusalOf([](ImportReport&) -> Mesh {
    std::fprintf(stderr, "some noise\nai_assert failure in Triangulate\n");
    std::abort();
  });
  CHECK(aborted.rfind("car.ply: the importer (assimp) crashed on this file (signal 6", 0) == 0);
  CHECK(aborted.find("ai_assert failure in Triangulate); refused") != std::string::npos);
  CHECK(aborted.find("some noise") == std::string::npos);
  // A hang: the child's CPU time limit ends it.
  const std::string hung = refusalOf(
      [](ImportReport&) -> Mesh {
        volatile unsigned long spin = 0;
        for (;;) spin = spin + 1;
      },
      1);
  CHECK(hung.rfind("car.ply: the importer (assimp) ran past its limit of 1 s of CPU time", 0) == 0);
  // An exit without an answer.
  CHECK(refusalOf([](ImportReport&) -> Mesh {
          std::_Exit(0);
        }).find("stopped on this file without an answer") != std::string::npos);
  // The read's own refusal comes back as itself; another exception as a failure, not a refusal.
  CHECK(refusalOf([](ImportReport&) -> Mesh { throw deform::InputError("car.ply: no triangles"); }) ==
        "car.ply: no triangles");
  ImportReport report;
  CHECK_THROWS_AS(
      deform::readContained(
          "car.ply", [](ImportReport&) -> Mesh { throw std::runtime_error("out of memory"); }, report, 5),
      std::runtime_error);
  CHECK_THROWS_WITH(deform::readContained(
                        "car.ply", [](ImportReport&) -> Mesh { return {}; }, report, 0),
                    Catch::Contains("importer_cpu_limit_s"));
}

// Normals updated only around moved vertices equal a full recompute bit for bit.
#include <deform/builtin_meshes.hpp>
#include <deform/vertex_normals.hpp>

#include <catch2/catch.hpp>
#include <cstdint>

TEST_CASE("partial normal updates equal computeVertexNormals bit for bit", "[normals]") {
  deform::Mesh mesh = deform::makeSedan(5000).body;
  // Edge cases: a triangle naming a vertex twice (zero area) and a vertex in no triangle.
  mesh.triangles.push_back({0, 0, 1});
  mesh.positions_m.emplace_back(9.0f, 9.0f, 9.0f);
  deform::VertexNormals normals(mesh);
  normals.computeAll(mesh);
  deform::Mesh full = mesh;
  deform::computeVertexNormals(full);
  REQUIRE(mesh.normals == full.normals);

  uint64_t seed = 3;
  auto next = [&seed] {  // fixed LCG, uniform in [0, 1)
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(seed >> 11) / 9007199254740992.0;
  };
  for (int round = 0; round < 8; ++round) {
    const double share = round % 3 == 2 ? 0.6 : 0.02;
    std::vector<uint8_t> moved(mesh.positions_m.size(), 0);
    for (std::size_t v = 0; v < mesh.positions_m.size(); ++v) {
      if (next() >= share) continue;
      moved[v] = 1;
      mesh.positions_m[v] +=
          0.01f * Eigen::Vector3f(float(next() - 0.5), float(next() - 0.5), float(next() - 0.5));
    }
    const std::size_t recomputed = normals.update(mesh, moved);
    full = mesh;
    deform::computeVertexNormals(full);
    CAPTURE(round, recomputed);
    REQUIRE(mesh.normals == full.normals);
    if (share < 0.1) CHECK(recomputed < mesh.positions_m.size() / 2);
  }
  CHECK(normals.update(mesh, std::vector<uint8_t>(mesh.positions_m.size(), 0)) == 0);
}

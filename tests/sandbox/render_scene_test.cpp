// Which meshes the renderer may cull: only closed, consistently and outwardly wound ones.
#include <catch2/catch.hpp>

#include <deform/builtin_meshes.hpp>

#include <utility>

#include "render/marker.hpp"
#include "render/scene.hpp"

using sandbox::render::isClosedOutward;

TEST_CASE("isClosedOutward accepts closed outward meshes and nothing else", "[render]") {
  const deform::Mesh box = deform::makeBox({1.0, 2.0, 0.5}, 200);
  CHECK(isClosedOutward(box));
  CHECK(isClosedOutward(deform::makeWheelMesh(0.3, 0.2)));
  CHECK(isClosedOutward(deform::makeCan(2000)));

  deform::Mesh inside_out = box;
  for (auto& t : inside_out.triangles) std::swap(t[1], t[2]);
  CHECK_FALSE(isClosedOutward(inside_out));  // closed, but wound inwards

  deform::Mesh one_flipped = box;
  std::swap(one_flipped.triangles[5][1], one_flipped.triangles[5][2]);
  CHECK_FALSE(isClosedOutward(one_flipped));  // inconsistent winding

  deform::Mesh open = box;
  open.triangles.pop_back();
  CHECK_FALSE(isClosedOutward(open));  // a hole

  CHECK_FALSE(isClosedOutward(deform::Mesh{}));
}

TEST_CASE("markerSphere is a closed sphere of the given radius around its centre", "[render]") {
  const sandbox::render::MeshData marker =
      sandbox::render::markerSphere({1.0f, 2.0f, 3.0f}, 0.25f, {1, 1, 1});
  CHECK(marker.closed);
  for (const Eigen::Vector3f& p : marker.positions_m) CHECK(p.norm() == Approx(0.25f).epsilon(1e-5));
  CHECK(marker.model.block<3, 1>(0, 3).isApprox(Eigen::Vector3f(1.0f, 2.0f, 3.0f)));
}

// The compact skin layouts (deform/src/skin_layout.cpp, issue 13): fixed-point weights whose integers sum
// exactly to the scale, a pass within 1e-5 m of a double-precision one, and the full pass equal bit for
// bit to the partial one.
#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>
#include <deform/skin.hpp>

#include <catch2/catch.hpp>
#include <cmath>

#include "skin_fixtures.hpp"

namespace {

using skin_test::Sedan;

using deform::SkinLayout;
using deform::SkinMethod;

/// Inverse-distance weights recomputed in double over the skin's own slots (Kenwright 2015, equation 1),
/// then the vertex moved in double: the reference the float, fixed-point pass is held to.
Eigen::Vector3d idwReference(const deform::Skin& skin, std::size_t j, const Eigen::Vector3d& v_m,
                             const std::vector<Eigen::Vector3d>& control_m,
                             const std::vector<Eigen::Vector3d>& displacement_m, bool& on_point) {
  double sum = 0;
  Eigen::Vector3d moved = Eigen::Vector3d::Zero();
  on_point = false;
  for (std::size_t k = 0; k < skin.influences(); ++k) {
    const uint32_t i = skin.slotIndex(j, k);
    const double d_m = (control_m[i] - v_m).norm();
    if (d_m < 1e-6) on_point = true;
    const double phi = std::pow(1.0 / d_m, skin.alpha());
    sum += phi;
    moved += phi * displacement_m[i];
  }
  return v_m + moved / sum;
}

}  // namespace

TEST_CASE("compact weights are fixed point and their integers sum exactly to one", "[skin][layout]") {
  Sedan s(20000);
  for (SkinMethod method : {SkinMethod::idw, SkinMethod::mls}) {
    CAPTURE(deform::skinMethodName(method));
    const auto skin = deform::Skin::build(s.rest(), s.control, {3.5, 8, 2, method});
    REQUIRE(skin.layout() == SkinLayout::compact);
    REQUIRE(skin.fixedPointWeights());
    CHECK(skin.indexBytes() == 1);  // 60 points: 8-bit indices
    CHECK(skin.weightScale() == (method == SkinMethod::idw ? 65535 : (1 << 21)));
    std::size_t wrong_sums = 0, negative = 0;
    for (std::size_t j = 0; j < skin.vertexCount(); ++j) {
      int64_t sum = 0;
      for (std::size_t k = 0; k < skin.influences(); ++k) {
        sum += skin.slotWeightFixed(j, k);
        negative += skin.slotWeightFixed(j, k) < 0;
      }
      wrong_sums += sum != skin.weightScale();
    }
    CHECK(wrong_sums == 0);
    if (method == SkinMethod::mls) CHECK(negative > 0);  // the signed form is exercised
    // 12 B rest + 12 B out + 8 slots of 3 B (idw: 8-bit index, 16-bit weight) or 4 B (mls: packed).
    CHECK(skin.bytesPerVertex() == (method == SkinMethod::idw ? 48u : 56u));
    const auto old = deform::Skin::build(s.rest(), s.control, {3.5, 8, 2, method, SkinLayout::float_weights});
    CHECK_FALSE(old.fixedPointWeights());
    CHECK(old.bytesPerVertex() == 72u);
  }
  // Past 256 points the indices widen to 16 bits; idw stays fixed point, mls keeps float weights.
  Sedan wide(20000, 300);
  const auto idw = deform::Skin::build(wide.rest(), wide.control, {3.5, 8, 2, SkinMethod::idw});
  const auto mls = deform::Skin::build(wide.rest(), wide.control, {3.5, 8, 2, SkinMethod::mls});
  CHECK(idw.indexBytes() == 2);
  CHECK(idw.fixedPointWeights());
  CHECK_FALSE(mls.fixedPointWeights());
}

TEST_CASE("the compact pass stays within 1e-5 m of a double-precision pass", "[skin][layout]") {
  for (std::size_t points : {60u, 300u}) {
    CAPTURE(points);
    Sedan s(20000, points);
    const auto displacement = s.dent();
    // idw: weights recomputed in double from the distances.
    const auto idw = deform::Skin::build(s.rest(), s.control, {3.5, 8, 2, SkinMethod::idw});
    std::vector<Eigen::Vector3f> out(s.rest().size());
    idw.deform(s.rest().data(), displacement.data(), out.data(), 2);
    double worst_m = 0;
    std::size_t compared = 0;
    for (std::size_t j = 0; j < out.size(); ++j) {
      bool on_point = false;
      const Eigen::Vector3d exact =
          idwReference(idw, j, s.rest()[j].cast<double>(), s.control, displacement, on_point);
      if (on_point) continue;  // (d_min / d)^alpha there; the reference above would divide by zero
      worst_m = std::max(worst_m, (out[j].cast<double>() - exact).norm());
      ++compared;
    }
    CAPTURE(worst_m);
    CHECK(compared > out.size() * 98 / 100);  // all but the vertices on a control point
    CHECK(worst_m <= 1e-5);
    // mls: the float weights as built (6e-8 relative from the double ones), accumulated in double.
    const auto mls = deform::Skin::build(s.rest(), s.control, {3.5, 8, 2, SkinMethod::mls});
    const auto mls_float =
        deform::Skin::build(s.rest(), s.control, {3.5, 8, 2, SkinMethod::mls, SkinLayout::float_weights});
    mls.deform(s.rest().data(), displacement.data(), out.data(), 2);
    double mls_worst_m = 0;
    for (std::size_t j = 0; j < out.size(); ++j) {
      Eigen::Vector3d exact = s.rest()[j].cast<double>();
      for (std::size_t k = 0; k < mls_float.influences(); ++k) {
        REQUIRE(mls_float.slotIndex(j, k) == mls.slotIndex(j, k));
        exact += static_cast<double>(mls_float.slotWeight(j, k)) * displacement[mls_float.slotIndex(j, k)];
      }
      mls_worst_m = std::max(mls_worst_m, (out[j].cast<double>() - exact).norm());
    }
    CAPTURE(mls_worst_m);
    CHECK(mls_worst_m <= 1e-5);
  }
}

TEST_CASE("the full pass equals the partial pass and any thread count bit for bit", "[skin][layout]") {
  // Every compact form through the SIMD and the scalar paths (a range's last vertex is scalar).
  Sedan s(100000);
  const auto displacement = s.dent();
  for (SkinMethod method : {SkinMethod::idw, SkinMethod::mls}) {
    CAPTURE(deform::skinMethodName(method));
    const auto skin = deform::Skin::build(s.rest(), s.control, {3.5, 8, 2, method});
    std::vector<Eigen::Vector3f> one(s.rest().size()), two(s.rest().size()), partial(s.rest().size());
    skin.deform(s.rest().data(), displacement.data(), one.data(), 1);
    skin.deform(s.rest().data(), displacement.data(), two.data(), 2);
    const std::vector<uint8_t> all(s.control.size(), 1);
    partial = s.rest();
    skin.deformMoved(s.rest().data(), displacement.data(), all, partial.data(), 3);
    CHECK(one == two);
    CHECK(one == partial);
    CHECK(one != s.rest());
    // One control point moved: the vertices it touches fall in runs, each of which ends in the scalar
    // form where the full pass took the SIMD one (AVX2 where the machine has it, else SSE): every such
    // vertex must come out the same to the bit (100-151 runs here).
    for (std::size_t point : {std::size_t{0}, s.control.size() / 2}) {
      std::vector<uint8_t> one_point(s.control.size(), 0);
      one_point[point] = 1;
      std::vector<uint8_t> recomputed;
      partial = s.rest();
      const std::size_t count =
          skin.deformMoved(s.rest().data(), displacement.data(), one_point, partial.data(), 1, &recomputed);
      REQUIRE(count > 100);
      std::size_t run_ends = 0, differing = 0;
      for (std::size_t j = 0; j < recomputed.size(); ++j) {
        if (!recomputed[j]) continue;
        run_ends += j + 1 == recomputed.size() || !recomputed[j + 1];
        differing += !(partial[j] == one[j]);
      }
      CAPTURE(point, count, run_ends);
      CHECK(run_ends > 50);  // the scalar form met many times
      CHECK(differing == 0);
    }
  }
}

// The constraint projections and the plastic return map alone (deform/constraints.hpp).
#include <catch2/catch.hpp>
#include <deform/constraints.hpp>

#include <algorithm>
#include <random>

using deform::PlasticLaw;

TEST_CASE("a rigid distance constraint is met in one projection, moving by inverse mass", "[dynamics]") {
  Eigen::Vector3d a(0, 0, 0), b(2, 0, 0);
  double lambda = 0;
  const double c =
      deform::projectDistance(a, b, 1.0, 3.0, 1.0, deform::distanceFactors(1.0, 3.0, 0.0, 1.0), lambda);
  CHECK(c == Approx(1.0));
  CHECK((a - b).norm() == Approx(1.0).margin(1e-15));
  CHECK(a.x() == Approx(0.25));  // a takes 1/4 of the correction, b 3/4
  CHECK(b.x() == Approx(1.25));
}

TEST_CASE("a compliant spoke under a constant load settles at alpha m g whatever the step", "[dynamics]") {
  // One point mass hanging from the core on a spoke: XPBD's fixed point is exactly the spring's static
  // deflection C = alpha m g (Macklin 2016: compliance is the inverse stiffness, independent of h).
  const double mass_kg = 2.0, compliance = 1e-4, g = 9.81;
  for (double h : {1.0 / 60, 1.0 / 600, 1.0 / 6000}) {
    Eigen::Vector3d x(0, 0, -1), v(0, 0, 0);
    Eigen::Vector3d core(0, 0, 0);
    for (int k = 0; k < static_cast<int>(3.0 / h); ++k) {
      const Eigen::Vector3d previous = x;
      v = v * std::exp(-20.0 * h) + Eigen::Vector3d(0, 0, -g * h);
      x += h * v;
      double lambda = 0;
      deform::projectDistance(x, core, 1.0 / mass_kg, 0.0, 1.0,
                              deform::distanceFactors(1.0 / mass_kg, 0.0, compliance, 1.0 / (h * h)), lambda);
      v = (x - previous) / h;
    }
    INFO("h = " << h);
    CHECK(-x.z() - 1.0 == Approx(compliance * mass_kg * g).epsilon(1e-6));
  }
}

TEST_CASE("the plastic return map: elastic below yield, flows by the excess above, clamped", "[dynamics]") {
  const deform::YieldLimits yield{0.02, 0.02};
  const PlasticLaw law{0.0, 0.5, 1.5};
  CHECK(deform::plasticRestLength(1.019, 1.0, 1.0, yield, law) == 1.0);  // below yield: untouched
  CHECK(deform::plasticRestLength(0.981, 1.0, 1.0, yield, law) == 1.0);
  CHECK(deform::plasticRestLength(1.10, 1.0, 1.0, yield, law) == Approx(1.08));  // excess 0.08 taken
  CHECK(deform::plasticRestLength(0.90, 1.0, 1.0, yield, law) == Approx(0.92));
  CHECK(deform::plasticRestLength(0.10, 1.0, 1.0, yield, law) == Approx(0.5));  // clamp: never below half
  CHECK(deform::plasticRestLength(9.0, 1.0, 1.0, yield, law) == Approx(1.5));
  // Hardening: with H = 1 half the excess flows, and the yield grows with the plastic elongation taken.
  const PlasticLaw hard{1.0, 0.5, 1.5};
  CHECK(deform::plasticRestLength(1.10, 1.0, 1.0, yield, hard) == Approx(1.04));
  CHECK(deform::plasticRestLength(1.10, 1.04, 1.0, yield, hard) == 1.04);  // e = 0.06 = 0.02 + 0.04
  // Yield limits fixed by the original geometry: a column shortened by half yields at the same
  // elongation (force), not at half of it.
  CHECK(deform::plasticRestLength(0.519, 0.5, 1.0, yield, law) == 0.5);
  // Asymmetric: a panel folds under a small shortening but stretches only past its tension limit.
  const deform::YieldLimits panel{0.05, 0.001};
  CHECK(deform::plasticRestLength(1.04, 1.0, 1.0, panel, law) == 1.0);
  CHECK(deform::plasticRestLength(0.99, 1.0, 1.0, panel, law) == Approx(0.991));
}

TEST_CASE("the cached elastic band never skips a flow, and is tight to 1e-8", "[dynamics]") {
  // plasticity() skips a constraint whose squared length is inside its band: that must give exactly the
  // return map's answer (no flow) for every length inside, and the band must reach the yield bounds.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int inside = 0, outside_flowed = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const double original = 0.01 + unit(random);
    const double rest = original * (0.5 + unit(random));
    const deform::YieldLimits yield{original * 0.1 * unit(random), original * 0.1 * unit(random)};
    const PlasticLaw law{trial % 3 == 0 ? 0.0 : unit(random), 0.4, 1.6};
    const deform::ElasticBand band = deform::elasticBand(rest, original, yield, law);
    const double taken = law.hardening * std::abs(rest - original);
    const double longest = rest + yield.stretch_m + taken, shortest = rest - yield.shorten_m - taken;
    for (int j = 0; j < 50; ++j) {
      const double length =  // a length, never negative
          std::max(0.0, (shortest - 0.1 * original) + unit(random) * (longest - shortest + 0.2 * original));
      if (band.holds(length * length)) {
        ++inside;
        REQUIRE(deform::plasticRestLength(length, rest, original, yield, law) == rest);
      }
    }
    // Just beyond either bound (by 1e-8 relative) the band no longer holds, and the rest length flows.
    for (const double beyond : {longest * (1 + 1e-8), shortest * (1 - 1e-8)}) {
      if (!(beyond > 0)) continue;
      REQUIRE_FALSE(band.holds(beyond * beyond));
      outside_flowed += deform::plasticRestLength(beyond, rest, original, yield, law) != rest;
    }
  }
  CHECK(inside > 10000);
  CHECK(outside_flowed > 3000);
  // A rest length the return map never moves (zero or negative) has a band that always holds.
  CHECK(deform::elasticBand(0.0, 1.0, {0.01, 0.01}, PlasticLaw{0, 0.5, 1.5}).holds(1e6));
}

namespace {

/// Seeded random draws for the shortcut tests (every run checks the same cases).
struct Draws {
  explicit Draws(unsigned seed) : random(seed) {}
  double unit() { return uniform(random); }
  Eigen::Vector3d gaussian() { return {gauss(random), gauss(random), gauss(random)}; }
  Eigen::Vector3d direction() { return gaussian().normalized(); }
  std::mt19937 random;
  std::normal_distribution<double> gauss{0.0, 1.0};
  std::uniform_real_distribution<double> uniform{0.0, 1.0};
};

}  // namespace

TEST_CASE("a column called surely elastic never flows", "[dynamics]") {
  Draws draw(11);
  int sure = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Eigen::Vector3d normal = draw.direction();
    const Eigen::Vector3d original = draw.gaussian();
    const Eigen::Vector3d rest = original - 0.05 * draw.unit() * normal;
    const deform::YieldLimits yield{0.02 * draw.unit(), 0.02 * draw.unit()};
    const PlasticLaw law{trial % 2 == 0 ? 0.0 : draw.unit(), 0.2, 1.0};
    const Eigen::Vector3d elastic = 0.03 * draw.unit() * draw.gaussian();
    if (!deform::columnSurelyElastic(normal, elastic, yield)) continue;
    ++sure;
    REQUIRE(deform::plasticColumnRest(rest + elastic, rest, original, normal, 0.5, yield, law) == rest);
  }
  CHECK(sure > 1000);
}

TEST_CASE("a column multiplier called surely within its limit is never clamped", "[dynamics]") {
  // The force-limited sweep skips the limit for such a multiplier: the full projection (the limit
  // evaluated) must then move the point and the multiplier exactly as the shortcut does.
  Draws draw(13);
  int sure = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Eigen::Vector3d normal = draw.direction();
    const deform::YieldLimits yield{0.02 * draw.unit(), 0.02 * draw.unit()};
    const double to_lambda = 1e-3 * draw.unit(), taken = trial % 2 == 0 ? 0.0 : 0.01 * draw.unit();
    const bool bottomed = trial % 5 == 0;
    const Eigen::Vector3d target = draw.gaussian();
    const Eigen::Vector3d start = target + 1e-4 * draw.gaussian();
    const double w = 1.0 + draw.unit(), w_core = 0.01 * draw.unit(), alpha_tilde = draw.unit();
    auto limit = [&](const Eigen::Vector3d& push) {
      if (bottomed && normal.dot(push) > 0) return HUGE_VAL;
      return to_lambda * deform::columnYield_m(normal, -push, yield, taken);
    };
    Eigen::Vector3d full_x = start, full_lambda{0, 0, 0};
    deform::projectColumn(full_x, target, w, w_core, alpha_tilde, full_lambda, limit);
    bool said = false;
    Eigen::Vector3d short_x = start, short_lambda{0, 0, 0};
    deform::projectColumn(short_x, target, w, w_core, alpha_tilde, short_lambda, limit,
                          [&](const Eigen::Vector3d& next) {
                            said = deform::columnSurelyWithinLimit(normal, next, yield, to_lambda, bottomed);
                            return said;
                          });
    REQUIRE(short_x == full_x);
    REQUIRE(short_lambda == full_lambda);
    sure += said;
  }
  CHECK(sure > 1000);
  CHECK(sure < 20000);  // and the limit does bind on some
}

TEST_CASE("the visual constraint projects onto the ball around the start", "[dynamics]") {
  Eigen::Vector3d x(3, 4, 0);
  CHECK(deform::projectVisual(x, Eigen::Vector3d::Zero(), 1.0));
  CHECK(x.norm() == Approx(1.0));
  CHECK(x.x() == Approx(0.6));
  CHECK_FALSE(deform::projectVisual(x, Eigen::Vector3d::Zero(), 2.0));
}

// Determinism (DESIGN.md section 7): same state and inputs, same hash; a snapshot restored mid-run
// continues bit-identically; the compact damage record restores the shape within 0.1 mm.
#include "fixtures.hpp"

#include <catch2/catch.hpp>
#include <deform/damage.hpp>
#include <deform/deformable_body.hpp>

using namespace deform;
using namespace dynamics_test;

namespace {

/// A crash: a box driven into the front, an impulse now and then, braking and a turn.
StepInputs crashInputs(int step) {
  StepInputs in;
  const double reach = 1.0 - 0.002 * std::min(step, 100);
  in.contacts.push_back(BoxShape{{reach + 1.0, 0.1, 0}, Eigen::Matrix3d::Identity(), {1.0, 0.4, 0.4}});
  if (step % 7 == 0) in.impulses.push_back({static_cast<uint32_t>(step % 40), Eigen::Vector3d(-50, 20, 10)});
  in.chassis.acceleration_mps2 = {-30, 2, 0};
  in.chassis.angular_velocity_radps = {0, 0, 0.3};
  in.chassis.gravity_mps2 = {0, 0, -9.81};
  return in;
}

std::shared_ptr<const BodySettings> crashBody(bool anchored_columns = false) {
  BodyDescription d;
  d.max_deviation_m = 0.15;
  d.anchored_columns = anchored_columns;
  return makeSettings(sphereHull(162), 1500.0, d, UniformMaterial{1e-6, 1e-5, 1e-5, 0.01});
}

}  // namespace

TEST_CASE("two runs from the same state and inputs give the same hash", "[dynamics]") {
  const auto settings = crashBody();
  DeformableBody a(settings), b(settings);
  for (int k = 0; k < 150; ++k) {
    a.step(crashInputs(k), 1.0 / 120);
    b.step(crashInputs(k), 1.0 / 120);
  }
  CHECK(a.state().plastic_work_J > 0);
  CHECK(hashState(a.state()) == hashState(b.state()));
  CHECK(hashState(a.state()) != hashState(restState(*settings)));
}

TEST_CASE("saving and restoring mid-run then continuing gives the same hash as never stopping",
          "[dynamics]") {
  const auto settings = crashBody();
  DeformableBody straight(settings);
  for (int k = 0; k < 200; ++k) straight.step(crashInputs(k), 1.0 / 120);

  DeformableBody first(settings);
  for (int k = 0; k < 80; ++k) first.step(crashInputs(k), 1.0 / 120);
  const std::vector<uint8_t> snapshot = saveState(first.state());
  DeformableBody second(settings);  // a fresh body: no scratch carried over
  second.setState(restoreState(*settings, snapshot));
  CHECK(hashState(second.state()) == hashState(first.state()));
  for (int k = 80; k < 200; ++k) second.step(crashInputs(k), 1.0 / 120);
  CHECK(hashState(second.state()) == hashState(straight.state()));

  std::vector<uint8_t> broken = snapshot;
  broken.resize(broken.size() / 2);
  CHECK_THROWS_WITH(restoreState(*settings, broken), Catch::Contains("truncated"));
}

TEST_CASE("the quantised damage record restores the shape within 0.1 mm", "[dynamics]") {
  const bool anchored = GENERATE(false, true);  // spokes' rest lengths, or the columns' rest places
  INFO((anchored ? "anchored columns" : "spokes"));
  const auto settings = crashBody(anchored);
  DeformableBody body(settings);
  for (int k = 0; k < 150; ++k) body.step(crashInputs(k), 1.0 / 120);
  for (int k = 0; k < 120; ++k) body.step({}, 1.0 / 120);  // settle
  const std::vector<uint8_t> record = encodeDamage(*settings, body.state());
  const BodyState restored = decodeDamage(*settings, record);
  double worst_position = 0, worst_rest = 0;
  for (std::size_t i = 0; i < settings->pointCount(); ++i)
    worst_position = std::max(worst_position, (restored.positions_m[i] - body.state().positions_m[i]).norm());
  for (std::size_t k = 0; k < settings->edges.size(); ++k)
    worst_rest = std::max(worst_rest, std::abs(restored.edge_rest_m[k] - body.state().edge_rest_m[k]));
  for (std::size_t k = 0; k < settings->spokes.size(); ++k)
    worst_rest = std::max(worst_rest, std::abs(restored.spoke_rest_m[k] - body.state().spoke_rest_m[k]));
  double worst_column = 0;  // each coordinate is within half a quantum
  for (std::size_t k = 0; k < settings->spokes.size(); ++k)
    worst_column = std::max(worst_column, (restored.column_rest_m[k] - body.state().column_rest_m[k]).norm());
  const std::size_t snapshot_bytes = saveState(body.state()).size();
  WARN("damage record " << record.size() << " bytes (full snapshot " << snapshot_bytes
                        << " bytes); worst position error " << worst_position * 1e3 << " mm, rest length "
                        << worst_rest * 1e3 << " mm");
  CHECK(maxDeviation(*settings, body.state()) > 0.01);  // there is a dent to record
  CHECK(worst_position <= 1e-4);
  CHECK(worst_rest <= 0.5e-4 + 1e-12);
  CHECK(worst_column <= 1e-4);
  if (anchored) {  // the columns flowed: their rest places are part of the dent to record
    double flowed_m = 0;
    for (std::size_t k = 0; k < settings->spokes.size(); ++k)
      flowed_m = std::max(flowed_m, (body.state().column_rest_m[k] - settings->rest_positions_m[k]).norm());
    CHECK(flowed_m > 0.01);
  }
  CHECK(restored.plastic_work_J == body.state().plastic_work_J);
  CHECK(record.size() < snapshot_bytes / 4);
  // An undamaged body records almost nothing.
  CHECK(encodeDamage(*settings, restState(*settings)).size() < 32);
}

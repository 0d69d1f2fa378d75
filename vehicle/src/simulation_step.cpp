// Simulation's step (simulation.hpp): ODE, then every car's deformation, the cars that touch nothing
// that moves in parallel (setThreads), with the same state on any number of threads.
#include "simulation_impl.hpp"

#include <deform/error.hpp>

#include <algorithm>
#include <chrono>
#include <exception>
#include <string>

namespace vehicle {
namespace {

using Clock = std::chrono::steady_clock;

double ms(Clock::duration d) {
  return std::chrono::duration<double, std::milli>(d).count();
}

// What a free obstacle (a knocked tree, a pushed box) may travel in one step, at most [m]: 1 m at 60 Hz
// is 60 m/s. Its velocity is not the world's to tell; a generous bound keeps the broad phase safe.
constexpr double kFreeObstacleTravel_m = 1.0;
// Added to every box: what a step's contact detection reaches beyond the surfaces [m].
constexpr double kBroadPhaseMargin_m = 0.05;
// The wake load an idle body is held asleep with: no change of load wakes it [m/s^2].
constexpr double kNeverWake_mps2 = 1e300;

// Time of one car's parallel part, per stage [ms].
struct CarLaps {
  double metrics_ms = 0, coupling_ms = 0, deform_ms = 0;
};

}  // namespace

void Simulation::setThreads(int threads) {
  if (threads < 1) throw deform::InputError("threads: must be >= 1 (got " + std::to_string(threads) + ")");
  impl_->threads = threads;
}

int Simulation::threads() const {
  return impl_->threads;
}

std::vector<uint8_t> Simulation::Impl::coupledCars() const {
  std::vector<uint8_t> coupled(cars.size(), 0);
  auto mark = [&](EntityRef self, EntityRef other) {
    if (self.kind != EntityRef::Kind::Car || self.index >= index_of.size() || index_of[self.index] < 0)
      return;
    if (other.kind == EntityRef::Kind::Car || world.obstacleIsDynamic(other.index))
      coupled[static_cast<std::size_t>(index_of[self.index])] = 1;
  };
  for (const ContactPoint& c : world.contacts()) {
    mark(c.a, c.b);
    mark(c.b, c.a);
  }
  return coupled;
}

void Simulation::Impl::updateBoxes() {
  car_boxes.assign(world.carCount(), Box{});
  for (CarId c = 0; c < world.carCount(); ++c) {
    const bool deforms = c < index_of.size() && index_of[c] >= 0;
    const std::vector<Eigen::Vector3d>& points =
        deforms ? of(c).world_shape.vertices_m : world.shapeOf({EntityRef::Kind::Car, c}).vertices_m;
    const Eigen::Vector3d centre = world.car(c).bodyPose().position_m;
    car_boxes[c] = points.empty() ? Box{centre, centre} : boxOf(points);
  }
  car_grid.build(car_boxes, 8.0);
  fastest_car_mps = fastest_turn_radps = largest_half_diagonal_m = 0;
  for (CarId c = 0; c < world.carCount(); ++c) {
    fastest_car_mps = std::max(fastest_car_mps, car_motion[c].velocity_mps.norm());
    fastest_turn_radps = std::max(fastest_turn_radps, car_motion[c].omega_radps.norm());
    largest_half_diagonal_m = std::max(largest_half_diagonal_m, car_boxes[c].halfDiagonal_m());
  }
  obstacle_boxes.assign(world.obstacleCount(), Box{});
  for (ObstacleId o = 0; o < world.obstacleCount(); ++o)
    if (world.obstacleKind(o) != ObstacleKind::Ground) obstacle_boxes[o] = boxOf(world.obstacleShape(o));
}

std::vector<uint8_t> Simulation::Impl::idleCars() const {
  const double dt = world.fixedDt_s();
  // Every car's box grown by the step's travel: its speed and its turn at its furthest corner.
  std::vector<Box> grown_cars;
  for (CarId c = 0; c < world.carCount(); ++c) {
    const Car& car = world.car(c);
    const Box& box = car_boxes[c];
    const Eigen::Vector3d centre = car.bodyPose().position_m;
    const double radius_m = (centre - box.min_m).cwiseAbs().cwiseMax((box.max_m - centre).cwiseAbs()).norm();
    const double travel_m = (car.velocity_mps().norm() + car.angularVelocity_rad_s().norm() * radius_m) * dt;
    grown_cars.push_back(box.grown(travel_m + kBroadPhaseMargin_m));
  }
  std::vector<Box> obstacle_grown;
  for (ObstacleId o = 0; o < world.obstacleCount(); ++o) {
    if (world.obstacleKind(o) == ObstacleKind::Ground) continue;
    const double grow_m = kBroadPhaseMargin_m + (world.obstacleIsDynamic(o) ? kFreeObstacleTravel_m : 0.0);
    obstacle_grown.push_back(obstacle_boxes[o].grown(grow_m));
  }
  std::vector<uint8_t> idle(cars.size(), 1);
  BoxGrid grid;  // the boxes that overlap share a cell: each car tests its cells' boxes, not every car's
  grid.build(grown_cars, 8.0);
  std::vector<uint32_t> near;
  for (std::size_t i = 0; i < cars.size(); ++i) {
    const Box& mine = grown_cars[cars[i]->id];
    grid.near(mine, near);
    for (const uint32_t c : near)
      if (c != cars[i]->id && mine.overlaps(grown_cars[c])) {
        idle[i] = 0;
        break;
      }
    for (const Box& b : obstacle_grown)
      if (idle[i] && mine.overlaps(b)) idle[i] = 0;
  }
  // Any contact but the ground's (the boxes should have said so already).
  auto busy = [&](EntityRef self, EntityRef other) {
    if (self.kind != EntityRef::Kind::Car || self.index >= index_of.size() || index_of[self.index] < 0)
      return;
    if (other.kind == EntityRef::Kind::Car || world.obstacleKind(other.index) != ObstacleKind::Ground)
      idle[static_cast<std::size_t>(index_of[self.index])] = 0;
  };
  for (const ContactPoint& c : world.contacts()) {
    busy(c.a, c.b);
    busy(c.b, c.a);
  }
  return idle;
}

void Simulation::Impl::holdAsleep(DeformableCar& dc, bool idle) const {
  deform::SolverParams params = dc.body->params();
  const double wake_mps2 = idle ? kNeverWake_mps2 : deform::SolverParams{}.wake_load_mps2;
  if (params.wake_load_mps2 == wake_mps2) return;
  params.wake_load_mps2 = wake_mps2;
  dc.body->setParams(params);
}

void Simulation::step() {
  Impl& m = *impl_;
  auto t = Clock::now();
  StepTimings timings;
  // Adds the time since the last lap to `stage` [ms].
  auto lap = [&t](double& stage_ms) {
    const auto now = Clock::now();
    stage_ms += ms(now - t);
    t = now;
  };
  // The crush forces found last step act during this one (on the car, and their reaction on free bodies).
  const std::size_t n = m.cars.size();
  std::vector<Eigen::Vector3d> velocity_before, omega_before;
  std::vector<double> kinetic_before;
  m.car_velocity_before.clear();
  for (CarId c = 0; c < m.world.carCount(); ++c)
    m.car_velocity_before.push_back(m.world.car(c).velocity_mps());
  for (auto& dc : m.cars) {
    const Car& car = m.world.car(dc->id);
    velocity_before.push_back(car.velocity_mps());
    omega_before.push_back(car.angularVelocity_rad_s());
    kinetic_before.push_back(m.carKineticEnergy(*dc));
  }
  lap(timings.metrics_ms);
  m.world.step();
  const WorldTimings world = m.world.lastTimings();
  timings.tyres_ms = world.tyres_ms;
  timings.collide_ms = world.collide_ms;
  timings.solve_ms = world.solve_ms;
  t = Clock::now();
  for (auto& dc : m.cars) dc->world_shape = m.snapshotShape(*dc);
  m.car_motion.resize(m.world.carCount());
  for (CarId c = 0; c < m.world.carCount(); ++c) m.refreshMotion(c);
  m.updateBoxes();
  const std::vector<uint8_t> coupled = m.coupledCars();
  bool any_skips = false;
  for (const auto& dc : m.cars) any_skips = any_skips || dc->settings.skip_when_idle;
  if (any_skips) {
    const std::vector<uint8_t> idle = m.idleCars();
    for (std::size_t i = 0; i < n; ++i)
      if (m.cars[i]->settings.skip_when_idle) m.holdAsleep(*m.cars[i], idle[i] != 0);
  }
  std::vector<std::size_t> alone;  // cars whose inputs and body step touch only themselves
  for (std::size_t i = 0; i < n; ++i)
    if (!coupled[i]) alone.push_back(i);
  lap(timings.coupling_ms);

  // Each car's energy account, inputs and body step; its reaction and metrics come after, in order.
  auto prepareAndSolve = [&](std::size_t i, CarLaps& laps) {
    DeformableCar& dc = *m.cars[i];
    auto c = Clock::now();
    auto carLap = [&c](double& stage_ms) {
      const auto now = Clock::now();
      stage_ms += ms(now - c);
      c = now;
    };
    dc.step_other_work_J = m.otherWork_J(dc, velocity_before[i], omega_before[i]);
    carLap(laps.metrics_ms);
    m.prepareCar(dc);
    carLap(laps.coupling_ms);
    m.solveCar(dc);
    carLap(laps.deform_ms);
  };
  std::vector<CarLaps> laps(n);
  std::vector<std::exception_ptr> errors(n);
  const auto parallel_start = Clock::now();
  const auto count = static_cast<std::ptrdiff_t>(alone.size());
#pragma omp parallel for num_threads(m.threads) schedule(dynamic, 1) if (m.threads > 1 && count > 1)
  for (std::ptrdiff_t k = 0; k < count; ++k) {
    const std::size_t i = alone[static_cast<std::size_t>(k)];
    try {
      prepareAndSolve(i, laps[i]);
    } catch (...) {
      errors[i] = std::current_exception();  // thrown below, in the cars' order
    }
  }
  // The parallel part's wall time, split over its stages as their time summed over the cars.
  const double parallel_ms = ms(Clock::now() - parallel_start);
  CarLaps sum;
  for (std::size_t i : alone) {
    sum.metrics_ms += laps[i].metrics_ms;
    sum.coupling_ms += laps[i].coupling_ms;
    sum.deform_ms += laps[i].deform_ms;
  }
  const double summed_ms = sum.metrics_ms + sum.coupling_ms + sum.deform_ms;
  if (summed_ms > 0) {
    timings.metrics_ms += parallel_ms * sum.metrics_ms / summed_ms;
    timings.coupling_ms += parallel_ms * sum.coupling_ms / summed_ms;
    timings.deform_ms += parallel_ms * sum.deform_ms / summed_ms;
  } else {
    timings.coupling_ms += parallel_ms;
  }

  t = Clock::now();
  for (std::size_t i = 0; i < n; ++i) {
    DeformableCar& dc = *m.cars[i];
    if (errors[i]) std::rethrow_exception(errors[i]);
    if (coupled[i]) {
      CarLaps own;
      prepareAndSolve(i, own);
      timings.metrics_ms += own.metrics_ms;
      timings.coupling_ms += own.coupling_ms;
      timings.deform_ms += own.deform_ms;
      t = Clock::now();
    }
    m.finishCar(dc);
    lap(timings.coupling_ms);
    m.updateMetrics(dc, velocity_before[i], kinetic_before[i]);
    lap(timings.metrics_ms);
  }
  m.timings = timings;
}

double Simulation::Impl::otherWork_J(const DeformableCar& dc, const Eigen::Vector3d& velocity_before,
                                     const Eigen::Vector3d& omega_before) const {
  const Car& car = world.car(dc.id);
  const double dt = world.fixedDt_s();
  // Work of every force on the chassis over the step, at the midpoint velocities of the points they act
  // at [J]: the crush force, and (for the energy balance) tyres and suspension, ODE contacts, drag and
  // gravity.
  const Eigen::Vector3d v_mid = 0.5 * (velocity_before + car.velocity_mps());
  const Eigen::Vector3d w_mid = 0.5 * (omega_before + car.angularVelocity_rad_s());
  const Eigen::Vector3d com = car.bodyPose().position_m;
  auto pointVelocity = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector3d(v_mid + w_mid.cross(p - com));
  };
  double taken_J = 0;  // by everything else
  for (const WheelState& w : car.wheels())
    if (w.in_contact) taken_J -= w.force_N.dot(pointVelocity(w.contact_point_m)) * dt;
  const EntityRef self{EntityRef::Kind::Car, dc.id};
  for (const ContactPoint& c : world.contacts()) {
    if (!(c.a == self) && !(c.b == self)) continue;
    const Eigen::Vector3d force = c.a == self ? c.force_on_a_N : Eigen::Vector3d(-c.force_on_a_N);
    taken_J -= force.dot(pointVelocity(c.position_m)) * dt;
  }
  const VehicleSettings& vs = car.settings();
  const Eigen::Vector3d drag =
      -0.5 * vs.air_density_kg_m3 * vs.drag_area_m2 * velocity_before.norm() * velocity_before;
  taken_J -= (drag + car.mass_kg() * world.settings().gravity_mps2).dot(v_mid) * dt;  // whole car's weight
  return taken_J;
}

}  // namespace vehicle

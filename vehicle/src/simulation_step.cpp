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
  // Idle (issue 42): nothing within the margin, so the body falls asleep once its points have been at rest
  // relative to the chassis for four of the damping's time constants (0.05 s at 80 1/s), and no change of
  // load wakes it. One quiet step is not enough: a body that starts at rest is slow in its first steps
  // before its load has moved it, and asleep unsettled it sagged when it woke, with energy the watch had
  // not seen (12 J created in random scene 4_0 of the campaign test). Not idle: deform's own sleep, its
  // delay and its wake load.
  deform::SolverParams params = dc.body->params();
  const deform::SolverParams defaults;
  const double wake_mps2 = idle ? kNeverWake_mps2 : defaults.wake_load_mps2;
  const double settled_s = dc.settings.damping > 0 ? 4.0 / dc.settings.damping : defaults.sleep_delay_s;
  const double delay_s = idle ? std::min(settled_s, defaults.sleep_delay_s) : defaults.sleep_delay_s;
  if (params.wake_load_mps2 == wake_mps2 && params.sleep_delay_s == delay_s) return;
  params.wake_load_mps2 = wake_mps2;
  params.sleep_delay_s = delay_s;
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
  std::vector<Eigen::Vector3d> position_before, velocity_before, omega_before;
  std::vector<double> kinetic_before;
  m.car_velocity_before.clear();
  for (CarId c = 0; c < m.world.carCount(); ++c)
    m.car_velocity_before.push_back(m.world.car(c).velocity_mps());
  for (auto& dc : m.cars) {
    const Car& car = m.world.car(dc->id);
    position_before.push_back(car.bodyPose().position_m);
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
  m.largest_ghost_m = 0;
  for (auto& dc : m.cars) {
    if (dc->world_shape.type != ShapeType::Convex) dc->world_shape = ObstacleShape{};
    m.snapshotInto(*dc, dc->world_shape);
    m.advanceGhost(*dc);  // before any car reads another's
    m.largest_ghost_m = std::max(
        m.largest_ghost_m, dc->ghost_offset_m.norm() + dc->ghost_velocity_mps.norm() * m.world.fixedDt_s());
  }
  m.car_motion.resize(m.world.carCount());
  for (CarId c = 0; c < m.world.carCount(); ++c) m.refreshMotion(c);
  m.updateBoxes();
  bool any_skips = false;
  for (const auto& dc : m.cars) any_skips = any_skips || dc->settings.skip_when_idle;
  std::vector<uint8_t> held_asleep(n, 0);  // per car: idle, and skip_when_idle holds its body asleep
  if (any_skips) {
    const std::vector<uint8_t> idle = m.idleCars();
    for (std::size_t i = 0; i < n; ++i)
      if (m.cars[i]->settings.skip_when_idle) {
        m.holdAsleep(*m.cars[i], idle[i] != 0);
        held_asleep[i] = idle[i];
      }
  }
  lap(timings.coupling_ms);

  // 1. Every car's energy account and inputs, from the world after ODE's step (reads only). 2. Groups of
  // cars whose bodies meet (partners), each a set of cars in order. 3. Each group's bodies step as one,
  // the groups in parallel (each touches only its own cars), bodies held asleep on this thread. 4. The
  // reactions and metrics, in order.
  std::vector<CarLaps> laps(n);
  std::vector<std::exception_ptr> errors(n);
  // Runs `work(k, laps)` for k < count on the threads; the parallel part's wall time is split over the
  // stages as their time summed over the cars.
  auto inParallel = [&](std::size_t count, auto&& work) {
    for (CarLaps& l : laps) l = {};
    const auto start = Clock::now();
    const auto total = static_cast<std::ptrdiff_t>(count);
#pragma omp parallel for num_threads(m.threads) schedule(dynamic, 1) if (m.threads > 1 && total > 1)
    for (std::ptrdiff_t k = 0; k < total; ++k) {
      try {
        work(static_cast<std::size_t>(k));
      } catch (...) {
        errors[static_cast<std::size_t>(k) < n ? static_cast<std::size_t>(k) : 0] = std::current_exception();
      }
    }
    const double parallel_ms = ms(Clock::now() - start);
    CarLaps sum;
    for (const CarLaps& l : laps) {
      sum.metrics_ms += l.metrics_ms;
      sum.coupling_ms += l.coupling_ms;
      sum.deform_ms += l.deform_ms;
    }
    const double summed_ms = sum.metrics_ms + sum.coupling_ms + sum.deform_ms;
    if (summed_ms > 0) {
      timings.metrics_ms += parallel_ms * sum.metrics_ms / summed_ms;
      timings.coupling_ms += parallel_ms * sum.coupling_ms / summed_ms;
      timings.deform_ms += parallel_ms * sum.deform_ms / summed_ms;
    } else {
      timings.coupling_ms += parallel_ms;
    }
    for (const std::exception_ptr& e : errors)  // the first in the cars' order
      if (e) std::rethrow_exception(e);
  };
  inParallel(n, [&](std::size_t i) {
    DeformableCar& dc = *m.cars[i];
    auto c = Clock::now();
    dc.step_other_work_J = m.otherWork_J(dc, velocity_before[i], omega_before[i]);
    const auto after_work = Clock::now();
    laps[i].metrics_ms += ms(after_work - c);
    m.prepareCar(dc);
    m.refineCar(dc);
    laps[i].coupling_ms += ms(Clock::now() - after_work);
  });

  t = Clock::now();
  const std::vector<std::vector<std::size_t>> groups = m.bodyGroups();
  lap(timings.coupling_ms);
  // A body held asleep with nothing to meet sleeps through its step in O(1): those step here, on this
  // thread (a parallel region cost more than their work: with 100 idle cars on a busy 2-core machine the
  // second thread made the step 2.5x slower than one thread, issue 42); the others in parallel. Each
  // group touches only its own cars, so the order does not change the state.
  std::vector<std::size_t> solving;  // indices into groups
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const std::size_t i = groups[g].front();
    if (groups[g].size() == 1 && held_asleep[i] && m.sleepsThrough(*m.cars[i])) {
      try {
        m.solveCar(*m.cars[i]);
      } catch (...) {
        errors[i] = std::current_exception();  // thrown below, in the cars' order
      }
    } else {
      solving.push_back(g);
    }
  }
  lap(timings.deform_ms);
  inParallel(solving.size(), [&](std::size_t k) {
    const auto c = Clock::now();
    const std::vector<std::size_t>& group = groups[solving[k]];
    try {
      if (group.size() == 1)
        m.solveCar(*m.cars[group.front()]);
      else
        m.solveGroup(group);
    } catch (...) {
      errors[group.front()] = std::current_exception();  // by its first car, as the asleep ones'
    }
    laps[group.front()].deform_ms += ms(Clock::now() - c);
  });

  t = Clock::now();
  for (std::size_t i = 0; i < n; ++i) {
    DeformableCar& dc = *m.cars[i];
    m.finishCar(dc);
    lap(timings.coupling_ms);
    m.updateMetrics(dc, position_before[i], velocity_before[i], kinetic_before[i]);
    lap(timings.metrics_ms);
  }
  // From the end of the first step: a scene may start a car's sideways speed by a push in it.
  if (m.watch.started)
    m.checkWatch();
  else
    m.startWatch();
  lap(timings.metrics_ms);
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

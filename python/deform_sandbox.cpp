// deform_sandbox: a scene played step by step from Python (pybind11), for closed-loop scenarios: read the
// cars' state, drive them, step. A thin layer over scenes::SceneRun, the runner `sandbox run` uses, so a
// Python run played to the end is the CLI's run (same state hash). Arrays are numpy arrays; the control
// points are a read-only view of the body's state (valid until the next step), the rest are copies.
#include <scenes/car_skin.hpp>
#include <scenes/scene_file.hpp>
#include <scenes/scene_run.hpp>
#include <scenes/skin_obstacles.hpp>

#include <deform/error.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace {

/// Scene keys from a Python dict {"vehicle.start.speed_kmh": 40}: each value as JSON text (a string as
/// the bare word the command line takes), then the command line's own parser (--set KEY=VALUE).
std::vector<scenes::Override> overridesOf(const py::dict& sets) {
  const py::object dumps = py::module_::import("json").attr("dumps");
  std::vector<scenes::Override> overrides;
  for (const auto& [key, value] : sets) {
    const std::string text =
        py::isinstance<py::str>(value) ? value.cast<std::string>() : dumps(value).cast<std::string>();
    overrides.push_back(scenes::parseOverride(py::str(key).cast<std::string>() + "=" + text));
  }
  return overrides;
}

/// A 3-vector as a new numpy array.
py::array_t<double> vector3(const Eigen::Vector3d& v) {
  py::array_t<double> out(3);
  auto a = out.mutable_unchecked<1>();
  for (py::ssize_t i = 0; i < 3; ++i) a(i) = v[static_cast<Eigen::Index>(i)];
  return out;
}

/// A played scene and the render skins asked for so far (built on the first mesh_vertices() of a car).
class Scene {
 public:
  Scene(const std::string& scene, const py::dict& sets)
      : run_(std::make_unique<scenes::SceneRun>(scenes::loadScene(scene, overridesOf(sets)))),
        skins_(run_->carCount()) {}

  scenes::SceneRun& run() { return *run_; }
  const scenes::SceneRun& run() const { return *run_; }

  /// The skin of car `car` with its deformed render mesh now (vehicle frame), as the renderer draws it: the
  /// skin of the control points, vertices inside an obstacle projected onto its surface (sandbox's
  /// deformedBody).
  const scenes::CarSkin& skin(std::size_t car) {
    const vehicle::Simulation& simulation = run_->simulation();
    const vehicle::CarId id = run_->carId(car);
    if (!skins_[car]) {
      skins_[car] = std::make_unique<scenes::CarSkin>(builds_.get(
          run_->model(car).body, simulation.controlRestPoints(id), simulation.deformationSettings(id)));
    }
    const std::vector<Eigen::Vector3d> displacements = simulation.controlDisplacements(id);
    if (displacements.size() != skins_[car]->skin().controlPointCount())  // refined: weights of its own
      skins_[car] = std::make_unique<scenes::CarSkin>(run_->model(car).body, simulation.controlRestPoints(id),
                                                      simulation.deformationSettings(id));
    scenes::SkinObstacles obstacles;
    obstacles.gather(simulation, id, skins_[car]->restBounds(),
                     skins_[car]->displacementBound_m(displacements));
    skins_[car]->update(displacements, obstacles.shapes());
    return *skins_[car];
  }

 private:
  std::unique_ptr<scenes::SceneRun> run_;
  scenes::CarSkinBuilds builds_;  ///< shared by the cars of one build
  std::vector<std::unique_ptr<scenes::CarSkin>> skins_;
};

/// One car of a Scene (holds the Scene alive).
struct Car {
  py::object owner;  ///< the Python Scene
  std::size_t index = 0;

  Scene& scene() const { return owner.cast<Scene&>(); }
  const vehicle::Car& chassis() const {
    const scenes::SceneRun& run = scene().run();
    return run.simulation().world().car(run.carId(index));
  }
};

py::dict summaryOf(const scenes::SceneRun& run) {
  nlohmann::json summary = run.summary();
  // What `sandbox run` adds to the run's summary for a headless run (sandbox/src/cmd_run.cpp).
  summary["frames"] = 0;
  summary["fps"] = run.scene().outputs.fps;
  summary["playback_speed"] = run.scene().outputs.playback_speed;
  return py::module_::import("json").attr("loads")(summary.dump()).cast<py::dict>();
}

}  // namespace

PYBIND11_MODULE(deform_sandbox, m) {
  m.doc() = "A deform sandbox scene played step by step from Python (scenes/README.md for every key).";
  // Bad scene keys, values, files: the command line's message (it names the file and the key).
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const deform::InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });

  py::class_<Car>(m, "Car", "One car of a scene: its state now, and drive() to take the wheel.")
      .def_property_readonly(
          "name", [](const Car& c) { return c.scene().run().scene().vehicles[c.index].name; },
          "The scene's name")
      .def_property_readonly(
          "position_m", [](const Car& c) { return vector3(c.chassis().vehiclePose().position_m); },
          "Origin of the vehicle frame in the world [m] (numpy, 3)")
      .def_property_readonly(
          "orientation_wxyz",
          [](const Car& c) {
            const Eigen::Quaterniond q = c.chassis().vehiclePose().orientation;
            py::array_t<double> out(4);
            auto a = out.mutable_unchecked<1>();
            a(0) = q.w();
            a(1) = q.x();
            a(2) = q.y();
            a(3) = q.z();
            return out;
          },
          "Rotation from the vehicle frame to the world, a unit quaternion (w, x, y, z)")
      .def_property_readonly(
          "pose",
          [](const Car& c) {
            const Eigen::Matrix4d t = c.chassis().vehiclePose().isometry().matrix();
            py::array_t<double> out({4, 4});
            auto a = out.mutable_unchecked<2>();
            for (py::ssize_t i = 0; i < 4; ++i)
              for (py::ssize_t j = 0; j < 4; ++j) a(i, j) = t(i, j);
            return out;
          },
          "The vehicle frame's pose as a 4 x 4 matrix (vehicle -> world) [m]")
      .def_property_readonly(
          "velocity_mps", [](const Car& c) { return vector3(c.chassis().velocity_mps()); },
          "Velocity of the centre of mass (world) [m/s] (numpy, 3)")
      .def_property_readonly(
          "angular_velocity_radps", [](const Car& c) { return vector3(c.chassis().angularVelocity_rad_s()); },
          "Angular velocity (world) [rad/s] (numpy, 3)")
      .def_property_readonly(
          "forward_speed_mps", [](const Car& c) { return c.chassis().forwardSpeed_mps(); },
          "Velocity along the chassis's X axis [m/s]")
      .def(
          "control_points",
          [](const Car& c) {
            const scenes::SceneRun& run = c.scene().run();
            const std::vector<Eigen::Vector3d>& points = run.simulation().controlPoints(run.carId(c.index));
            // A read-only view of the body's state, no copy: valid until the scene steps again.
            py::array_t<double> view(
                {static_cast<py::ssize_t>(points.size()), py::ssize_t{3}},
                {static_cast<py::ssize_t>(sizeof(Eigen::Vector3d)), static_cast<py::ssize_t>(sizeof(double))},
                points.empty() ? nullptr : points.front().data(), c.owner);
            py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
            return view;
          },
          "Control points now, vehicle frame [m] (N x 3, a read-only view: copy it to keep it past a step)")
      .def(
          "rest_control_points",
          [](const Car& c) {
            const scenes::SceneRun& run = c.scene().run();
            const std::vector<Eigen::Vector3d>& points =
                run.simulation().controlRestPoints(run.carId(c.index));
            py::array_t<double> out({static_cast<py::ssize_t>(points.size()), py::ssize_t{3}});
            auto a = out.mutable_unchecked<2>();
            for (std::size_t i = 0; i < points.size(); ++i)
              for (py::ssize_t k = 0; k < 3; ++k) a(static_cast<py::ssize_t>(i), k) = points[i][k];
            return out;
          },
          "Control points at rest, vehicle frame [m] (N x 3)")
      .def(
          "mesh_vertices",
          [](const Car& c) {
            const std::vector<Eigen::Vector3f>& positions = c.scene().skin(c.index).positions();
            py::array_t<float> out({static_cast<py::ssize_t>(positions.size()), py::ssize_t{3}});
            auto a = out.mutable_unchecked<2>();
            for (std::size_t j = 0; j < positions.size(); ++j)
              for (py::ssize_t k = 0; k < 3; ++k) a(static_cast<py::ssize_t>(j), k) = positions[j][k];
            return out;
          },
          "The dented render mesh now, vehicle frame [m] (V x 3 float32; skinned on request)")
      .def(
          "mesh_triangles",
          [](const Car& c) {
            const std::vector<deform::Triangle>& triangles = c.scene().run().model(c.index).body.triangles;
            py::array_t<uint32_t> out({static_cast<py::ssize_t>(triangles.size()), py::ssize_t{3}});
            auto a = out.mutable_unchecked<2>();
            for (std::size_t t = 0; t < triangles.size(); ++t)
              for (py::ssize_t k = 0; k < 3; ++k) a(static_cast<py::ssize_t>(t), k) = triangles[t][k];
            return out;
          },
          "The render mesh's triangles (T x 3 vertex indices)")
      .def(
          "drive",
          [](const Car& c, double throttle, double brake, double steering, bool handbrake, bool reverse) {
            const std::initializer_list<std::pair<const char*, double>> pedals = {
                {"throttle", throttle}, {"brake", brake}, {"steering", steering}};
            for (const auto& [name, value] : pedals) {
              if (!std::isfinite(value))
                throw deform::InputError(std::string(name) + ": must be finite (got " +
                                         std::to_string(value) + ")");
            }
            vehicle::DriverInput input;
            input.throttle = throttle;
            input.brake = brake;
            input.steering = steering;
            input.handbrake = handbrake;
            input.reverse = reverse;
            c.scene().run().overrideDriverInput(c.index, input);
          },
          py::arg("throttle") = 0.0, py::arg("brake") = 0.0, py::arg("steering") = 0.0,
          py::arg("handbrake") = false, py::arg("reverse") = false,
          "Inputs for the next steps, instead of the drive script: throttle and brake 0..1, steering -1 "
          "(right) "
          "..1 (left). Held until drive() again or release().")
      .def(
          "release", [](const Car& c) { c.scene().run().overrideDriverInput(c.index, std::nullopt); },
          "Hands the car back to its drive script.")
      .def_property_readonly(
          "metrics",
          [](const Car& c) {
            const nlohmann::json summary = c.scene().run().summary();
            return py::module_::import("json").attr("loads")(summary["cars"][c.index].dump());
          },
          "This car's entry of summary()['cars'] now");

  py::class_<Scene>(m, "Scene",
                    "A scene played step by step: Scene('wall_crash', set={'vehicle.start.speed_kmh': 40})")
      .def(py::init<const std::string&, const py::dict&>(), py::arg("scene"), py::arg("set") = py::dict(),
           "A shipped scene's name or a scene file, with scene keys overridden as `sandbox run --set` does. "
           "ValueError (the command line's message, naming the key) for a bad key or value.")
      .def_static(
          "resume",
          [](const std::string& path, const py::dict& sets, const std::optional<std::string>& scene) {
            const std::string source = scene ? *scene : scenes::stateFileSceneSource(path);
            py::object run = py::cast(Scene(source, sets));
            run.cast<Scene&>().run().restoreState(path);
            return run;
          },
          py::arg("path"), py::arg("set") = py::dict(), py::arg("scene") = py::none(),
          "The run saved by save_state(path), continuing bit for bit (`sandbox run --resume`). The scene is "
          "the one the file names unless given; `set` must repeat the saved run's keys.")
      .def(
          "step", [](Scene& s) { s.run().step(); }, "One fixed physics step (nothing once finished)")
      .def(
          "advance", [](Scene& s, double dt_s) { return s.run().advance(dt_s); }, py::arg("dt_s"),
          "A frame of dt_s from a frame clock: the fixed steps it adds up to; returns how many")
      .def(
          "run_to_end", [](Scene& s) { s.run().runToEnd(); }, "Steps to the end of the scene")
      .def_property_readonly(
          "time_s", [](const Scene& s) { return s.run().time_s(); }, "Simulated time [s]")
      .def_property_readonly(
          "duration_s", [](const Scene& s) { return s.run().scene().duration_s; }, "The scene's duration [s]")
      .def_property_readonly(
          "physics_hz", [](const Scene& s) { return s.run().scene().physics_hz; }, "Fixed physics rate [Hz]")
      .def_property_readonly(
          "steps", [](const Scene& s) { return s.run().steps(); }, "Steps taken")
      .def_property_readonly(
          "finished", [](const Scene& s) { return s.run().finished(); }, "The scene has reached its end")
      .def_property_readonly(
          "name", [](const Scene& s) { return s.run().scene().name; }, "The scene's name")
      .def_property_readonly(
          "cars",
          [](py::object self) {
            py::list cars;
            for (std::size_t i = 0; i < self.cast<Scene&>().run().carCount(); ++i) cars.append(Car{self, i});
            return cars;
          },
          "The scene's cars")
      .def_property_readonly(
          "obstacles",
          [](const Scene& s) {
            py::list out;
            for (const scenes::ObstacleConfig& o : s.run().scene().obstacles) {
              py::dict d;
              d["name"] = o.name;
              d["position_m"] = vector3(o.position_m);
              d["size_m"] = vector3(o.size_m);
              d["yaw_deg"] = o.yaw_deg;
              d["radius_m"] = o.radius_m;
              d["height_m"] = o.height_m;
              out.append(d);
            }
            return out;
          },
          "The scene's obstacles as placed: name, position_m (a wall's or box's centre, a post's base), "
          "size_m, "
          "yaw_deg, radius_m, height_m")
      .def(
          "obstacle_pose",
          [](const Scene& s, std::size_t index) {
            if (index >= s.run().scene().obstacles.size())
              throw deform::InputError("obstacle: the scene has " +
                                       std::to_string(s.run().scene().obstacles.size()) + " obstacle(s)");
            return vector3(s.run().simulation().world().obstaclePose(s.run().obstacleId(index)).position_m);
          },
          py::arg("index"), "Position of obstacle `index` (its shape's frame) in the world [m] (numpy, 3)")
      .def(
          "summary", [](const Scene& s) { return summaryOf(s.run()); },
          "The run's figures now: the dict `sandbox run` writes as summary.json")
      .def(
          "state_hash", [](const Scene& s) { return scenes::hashHex(s.run().stateHash()); },
          "The state hash (16 hex digits) `sandbox run` prints and writes")
      .def(
          "save_state", [](const Scene& s, const std::string& path) { s.run().saveState(path); },
          py::arg("path"),
          "Writes the whole state to `path` (`sandbox run --save-state`); Scene.resume(path) continues it");
}

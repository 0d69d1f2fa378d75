// Scene files: strict parsing with key paths, --set overrides, shipped scenes by name.
#include <scenes/deformation_budget.hpp>
#include <scenes/scene_file.hpp>

#include <deform/error.hpp>
#include <deform/mesh_import.hpp>
#include <deform/path_checks.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "json_reader.hpp"

namespace fs = std::filesystem;

namespace scenes {
namespace {

using detail::JsonObject;
using nlohmann::json;

constexpr double kHuge = 1e6;  // bound for positions and sizes [m]

// The presets are the budget's levels (deformation_budget.cpp), by name.
std::vector<std::string> presetNames() {
  std::vector<std::string> names;
  for (const DeformationLevel& level : deformationLevels()) names.push_back(level.name);
  return names;
}

// "${DEFORM_TEST_MESHES}/x.obj" -> the variable's value; relative paths against the scene's folder.
std::string resolveMeshPath(const std::string& spec, JsonObject& object, const std::string& key,
                            const std::string& base_dir) {
  if (spec.empty()) object.fail(key, "must not be empty (builtin:sedan, builtin:can, builtin:box or a file)");
  if (deform::isBuiltinSpec(spec)) return spec;
  std::string path = spec;
  const std::string variable = "${DEFORM_TEST_MESHES}";
  if (const auto at = path.find(variable); at != std::string::npos) {
    const char* value = std::getenv("DEFORM_TEST_MESHES");
    if (!value || !*value) {
      object.fail(key, "'" + spec +
                           "' needs DEFORM_TEST_MESHES set to the shared meshes folder (or give the file: "
                           "--set " +
                           object.keyPath(key) + "=/path/to/car.obj)");
    }
    path.replace(at, variable.size(), value);
  }
  fs::path p(path);
  if (p.is_relative()) p = fs::path(base_dir) / p;
  if (!deform::isRegularFile(p)) object.fail(key, "file not found: " + p.string());
  return p.string();
}

std::optional<std::string> axisKey(JsonObject& object, const std::string& key) {
  if (!object.has(key)) return std::nullopt;
  const std::string text = object.string(key, std::nullopt);
  try {
    (void)deform::parseAxis(text, key);
  } catch (const deform::InputError&) {
    object.fail(key, "unknown axis '" + text + "' (+x, -x, +y, -y, +z or -z)");
  }
  return text;
}

Eigen::Vector3f colourKey(JsonObject& object, const Eigen::Vector3f& fallback) {
  return object.vector3("colour", fallback.cast<double>(), 0.0, 1.0).cast<float>();
}

std::string regionNames(const std::vector<vehicle::RegionMaterial>& map) {
  std::string names;
  for (const auto& r : map) names += (names.empty() ? "" : ", ") + r.name;
  return names.empty() ? "none: material_map is uniform" : names;
}

/// vehicle.deformation.regions: per named region, the material members it sets and, optionally, where it
/// is (box_min, box_max in fractions of the car's bounding box). A new name needs a box.
void parseRegions(JsonObject& regions, std::vector<vehicle::RegionMaterial>& map) {
  for (const std::string& name : regions.keys()) {
    std::optional<JsonObject> object = regions.object(name, true);
    auto found = std::find_if(map.begin(), map.end(), [&](const auto& r) { return r.name == name; });
    if (found == map.end()) {
      if (!object->has("box_min") || !object->has("box_max"))
        regions.fail(name, "is not a region of the map (" + regionNames(map) +
                               "); a new region needs box_min and box_max");
      map.push_back({name, {}, {}});
      found = map.end() - 1;
    }
    if (object->has("box_min") || object->has("box_max")) {
      deform::Aabb box{object->vector3("box_min", std::nullopt, 0, 1),
                       object->vector3("box_max", std::nullopt, 0, 1)};
      if (!(box.min_m.array() <= box.max_m.array()).all())
        object->fail("box_max", "must not be below box_min on any axis");
      found->boxes = {box};
    }
    for (const vehicle::MaterialMember& member : vehicle::materialMembers())
      if (object->has(member.key))
        found->set(member.key, object->number(member.key, std::nullopt, member.min, member.max));
    object->finish();
  }
}

// The regions of material map `name`; `auto`, what a car gets unless its scene names one, is the sedan's for
// the built-in sedan (docs/CRASH_CALIBRATION.md, "Material map": its values and where they come from),
// uniform for any other mesh (a file car, the can, a box), whose regions nobody has placed.
std::vector<vehicle::RegionMaterial> materialMap(std::string name, const std::string& mesh) {
  if (name == "auto") name = mesh.rfind("builtin:sedan", 0) == 0 ? "sedan" : "uniform";
  return name == "sedan" ? vehicle::sedanMaterialMap() : std::vector<vehicle::RegionMaterial>{};
}

DeformationConfig parseDeformation(std::optional<JsonObject> object, vehicle::Coupling coupling,
                                   const std::string& mesh) {
  DeformationConfig d = *deformationPreset("balanced");
  d.settings.regions = materialMap("auto", mesh);
  if (object) {
    d = *deformationPreset(object->choice("preset", std::string("balanced"), presetNames()));
    vehicle::DeformationSettings& s = d.settings;
    s.control_points = static_cast<std::size_t>(
        object->integer("control_points", static_cast<long long>(s.control_points), 4, 5000));
    s.alpha = object->number("alpha", s.alpha, 0.5, 16);
    s.k_nearest =
        static_cast<std::size_t>(object->integer("k_nearest", static_cast<long long>(s.k_nearest), 0, 64));
    const std::string skin_method =
        object->choice("skin_method", std::string("auto"), {"auto", "idw", "mls", "spline"});
    d.skin_method_auto = skin_method == "auto";
    if (!d.skin_method_auto) deform::parseSkinMethod(skin_method, s.skin_method);
    if (skin_method == "spline" && s.control_points > deform::kSplineMostControlPoints)
      object->fail("skin_method",
                   "spline through every control point (evaluated at every lattice node each "
                   "frame): at most " +
                       std::to_string(deform::kSplineMostControlPoints) + " control points (got " +
                       std::to_string(s.control_points) + ")");
    s.substeps = static_cast<int>(object->integer("substeps", s.substeps, 1, 64));
    s.iterations = static_cast<int>(object->integer("iterations", s.iterations, 1, 64));
    s.max_deviation_m = object->number("max_deviation_m", s.max_deviation_m, 1e-4, 10);
    for (const vehicle::MaterialMember& member : vehicle::materialMembers())
      s.material.*(member.member) =
          object->number(member.key, s.material.*(member.member), member.min, member.max);
    s.regions =
        materialMap(object->choice("material_map", std::string("auto"), {"auto", "uniform", "sedan"}), mesh);
    if (auto regions = object->object("regions")) parseRegions(*regions, s.regions);
    s.shell_mass_fraction = object->number("shell_mass_fraction", s.shell_mass_fraction, 1e-3, 1);
    s.damping = object->number("damping", s.damping, 0, 1000);
    s.contact_friction = object->number("contact_friction", s.contact_friction, 0, 10);
    s.max_depenetration_mps = object->number("max_depenetration_mps", s.max_depenetration_mps, 0.01, 1e9);
    s.longest_contact_substep_s =
        object->number("longest_contact_substep_s", s.longest_contact_substep_s, 0, 1);
    s.crush_allowance_m = object->number("crush_allowance_m", s.crush_allowance_m, 0, 10);
    s.backstop = object->choice("backstop", std::string("rigid_parts"), {"rigid_parts", "shrunk_hull"}) ==
                         "shrunk_hull"
                     ? vehicle::Backstop::ShrunkHull
                     : vehicle::Backstop::RigidParts;
    // Each backstop has its own key: the other one's would be silently ignored.
    if (s.backstop == vehicle::Backstop::RigidParts && object->has("crush_allowance_m"))
      object->fail("crush_allowance_m",
                   "applies to backstop shrunk_hull only (the rigid parts are the stroke)");
    if (s.backstop == vehicle::Backstop::ShrunkHull && object->has("rigid_parts"))
      object->fail("rigid_parts", "applies to backstop rigid_parts only");
    if (object->has("rigid_parts")) {
      s.rigid_parts.clear();
      for (JsonObject& part : object->objects("rigid_parts")) {
        deform::Aabb box{part.vector3("box_min", std::nullopt, 0, 1),
                         part.vector3("box_max", std::nullopt, 0, 1)};
        if (!(box.min_m.array() <= box.max_m.array()).all())
          part.fail("box_max", "must not be below box_min on any axis");
        part.finish();
        s.rigid_parts.push_back(box);
      }
      if (s.rigid_parts.empty())
        object->fail("rigid_parts", "needs at least one box (or backstop shrunk_hull)");
    }
    s.inertial_scale = object->number("inertial_scale", s.inertial_scale, 0, 10);
    // Removed: a share of ODE's contact impulses with a plant handed to the nearest points, a dent no force
    // of the body made. Vegetation now meets the body as every free obstacle does.
    if (object->has("visual_impulse_scale"))
      object->fail("visual_impulse_scale",
                   "was removed: vegetation dents the body as every free obstacle does (delete the key)");
    s.yield_limited = object->boolean("yield_limited", s.yield_limited);
    s.anchored_columns = object->boolean("anchored_columns", s.anchored_columns);
    s.skip_when_idle = object->boolean("skip_when_idle", s.skip_when_idle);
    s.refine = object->boolean("refine", s.refine);
    s.contact_edge_m = object->number("contact_edge_m", s.contact_edge_m, 1e-3, 10);
    s.max_control_points = static_cast<std::size_t>(object->integer(
        "max_control_points", static_cast<long long>(std::max(s.max_control_points, s.control_points)),
        static_cast<long long>(s.control_points), 100000));
    object->finish();
  }
  d.settings.coupling = coupling;
  resolveSkinMethod(d);
  return d;
}

DriveKey parseDriveKey(JsonObject& key) {
  DriveKey k;
  k.t_s = key.number("t_s", std::nullopt, 0, kHuge);
  k.throttle = key.number("throttle", 0.0, 0, 1);
  k.brake = key.number("brake", 0.0, 0, 1);
  k.steering = key.number("steering", 0.0, -1, 1);
  k.handbrake = key.boolean("handbrake", false);
  if (key.has("target_speed_kmh")) k.target_speed_kmh = key.number("target_speed_kmh", std::nullopt, 0, 500);
  key.finish();
  return k;
}

DriveScript parseDrive(std::optional<JsonObject> object) {
  DriveScript script;
  if (!object) return script;
  // Shorthand: a target speed for the whole run.
  if (object->has("target_speed_kmh")) {
    DriveKey k;
    k.target_speed_kmh = object->number("target_speed_kmh", std::nullopt, 0, 500);
    script.keys.push_back(k);
  }
  for (JsonObject& key : object->objects("keys")) {
    script.keys.push_back(parseDriveKey(key));
    if (script.keys.size() > 1 && script.keys.back().t_s < script.keys[script.keys.size() - 2].t_s) {
      key.fail("t_s", "keys must be in time order (this one comes before the previous key)");
    }
  }
  object->finish();
  return script;
}

VehicleConfig parseVehicle(JsonObject& object, std::size_t index, const std::string& base_dir) {
  VehicleConfig v;
  v.name = object.string("name", "car" + std::to_string(index));
  v.mesh_scale = object.number("mesh_scale", 1.0, 1e-6, 1e6);
  v.mesh_up = axisKey(object, "mesh_up");
  v.mesh_forward = axisKey(object, "mesh_forward");
  v.mesh = resolveMeshPath(object.string("mesh", std::nullopt), object, "mesh", base_dir);
  v.mass_kg = object.number("mass_kg", std::nullopt, 0.01, 100000);
  v.collision_points = static_cast<std::size_t>(
      object.integer("collision_points", static_cast<long long>(v.collision_points), 8, 1000));
  v.wheels_in_body = object.choice("wheels", std::string("model"), {"model", "in_body"}) == "in_body";
  const bool visual = object.choice("coupling", std::nullopt, {"crush", "visual"}) == "visual";
  const vehicle::Coupling coupling = visual ? vehicle::Coupling::Visual : vehicle::Coupling::Crush;
  v.colour = colourKey(object, v.colour);
  JsonObject start = *object.object("start", true);
  v.start.position_m = start.vector3("position_m", Eigen::Vector3d::Zero(), -kHuge, kHuge, 0.0);
  v.start.heading_deg = start.number("heading_deg", 0.0, -360, 360);
  v.start.speed_kmh = start.number("speed_kmh", std::nullopt, -600, 600);
  v.start.lateral_speed_kmh = start.number("lateral_speed_kmh", 0.0, -600, 600);
  v.start.on_ground = start.boolean("on_ground", true);
  start.finish();
  v.deformation = parseDeformation(object.object("deformation"), coupling, v.mesh);
  v.drive = parseDrive(object.object("drive"));
  object.finish();
  return v;
}

ObstacleConfig parseObstacle(JsonObject& object, std::size_t index, const std::string& base_dir) {
  ObstacleConfig o;
  const std::string type =
      object.choice("type", std::nullopt, {"wall", "post", "vegetation", "ramp", "box", "mesh"});
  o.name = object.string("name", type + std::to_string(index));
  o.yaw_deg = object.number("yaw_deg", 0.0, -360, 360);
  o.friction = object.number("friction", type == "vegetation" ? 0.8 : type == "ramp" ? 1.0 : 0.6, 0, 10);
  if (type == "wall" || type == "box") {
    o.type = type == "wall" ? ObstacleType::Wall : ObstacleType::Box;
    o.size_m = object.vector3("size_m", std::nullopt, 1e-3, kHuge);
    o.position_m = object.vector3("position_m", std::nullopt, -kHuge, kHuge, o.size_m.z() / 2);
    if (o.type == ObstacleType::Box) o.mass_kg = object.number("mass_kg", 0.0, 0, 1e6);
    o.colour = colourKey(
        object, type == "wall" ? Eigen::Vector3f(0.58f, 0.57f, 0.55f) : Eigen::Vector3f(0.35f, 0.45f, 0.60f));
  } else if (type == "post" || type == "vegetation") {
    o.type = type == "post" ? ObstacleType::Post : ObstacleType::Vegetation;
    o.position_m = object.vector3("position_m", std::nullopt, -kHuge, kHuge, 0.0);
    o.radius_m = object.number("radius_m", std::nullopt, 1e-3, 100);
    o.height_m = object.number("height_m", std::nullopt, 1e-3, 1000);
    if (o.type == ObstacleType::Post) {
      o.capsule = object.choice("shape", std::string("cylinder"), {"cylinder", "capsule"}) == "capsule";
      o.colour = colourKey(object, {0.50f, 0.52f, 0.55f});
    } else {
      o.mass_kg = object.number("mass_kg", std::nullopt, 1e-3, 1e5);
      o.colour = colourKey(object, {0.20f, 0.50f, 0.18f});
    }
  } else if (type == "ramp") {
    o.type = ObstacleType::Ramp;
    o.position_m = object.vector3("position_m", std::nullopt, -kHuge, kHuge, 0.0);
    o.length_m = object.number("length_m", std::nullopt, 1e-3, 1000);
    o.width_m = object.number("width_m", std::nullopt, 1e-3, 1000);
    o.height_m = object.number("height_m", std::nullopt, 1e-3, 1000);
    o.colour = colourKey(object, {0.60f, 0.55f, 0.45f});
  } else {
    o.type = ObstacleType::Mesh;
    o.mesh_scale = object.number("mesh_scale", 1.0, 1e-6, 1e6);
    o.mesh = resolveMeshPath(object.string("mesh", std::nullopt), object, "mesh", base_dir);
    o.position_m = object.vector3("position_m", std::nullopt, -kHuge, kHuge, 0.0);
    o.mass_kg = object.number("mass_kg", 0.0, 0, 1e6);
    o.colour = colourKey(object, {0.70f, 0.70f, 0.68f});
  }
  object.finish();
  return o;
}

CameraConfig parseCamera(std::optional<JsonObject> object, std::size_t vehicles) {
  CameraConfig c;
  if (!object) return c;
  const std::string mode = object->choice("mode", std::string("chase"), {"chase", "side", "fixed"});
  c.mode = mode == "side" ? CameraMode::Side : mode == "fixed" ? CameraMode::Fixed : CameraMode::Chase;
  c.follow = static_cast<std::size_t>(object->integer("follow", 0, 0, static_cast<long long>(vehicles) - 1));
  c.distance_m = object->number("distance_m", c.distance_m, 0.01, 1000);
  c.height_m = object->number("height_m", c.height_m, -1000, 1000);
  c.eye_m = object->vector3("eye_m", c.eye_m, -kHuge, kHuge);
  c.target_m = object->vector3("target_m", c.target_m, -kHuge, kHuge);
  c.fov_deg = object->number("fov_deg", c.fov_deg, 5, 150);
  object->finish();
  return c;
}

OutputConfig parseOutputs(std::optional<JsonObject> object) {
  OutputConfig o;
  if (!object) return o;
  o.frames = object->boolean("frames", false);
  o.video = object->boolean("video", false);
  o.heatmap = object->boolean("heatmap", false);
  o.width = static_cast<int>(object->integer("width", o.width, 16, 8192));
  o.height = static_cast<int>(object->integer("height", o.height, 16, 8192));
  o.fps = object->number("fps", o.fps, 1, 1000);
  o.playback_speed = object->number("playback_speed", o.playback_speed, 1e-3, 1000);
  o.heatmap_full_scale_m = object->number("heatmap_full_scale_m", 0.0, 0, 100);
  o.samples = static_cast<int>(object->integer("samples", o.samples, 0, 16));
  object->finish();
  return o;
}

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw deform::InputError(path + ": cannot read the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Line and column of byte `offset` in `text` (1-based).
std::string lineColumn(const std::string& text, std::size_t offset) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < std::min(offset, text.size()); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

}  // namespace

void resolveSkinMethod(DeformationConfig& d) {
  // Once, for the run: a body that refines is skinned for the points it may grow to (mls's affine fit
  // through clustered fine points throws vertices about: pole_side refined from 60 points measured 3.5 mm
  // of surface crush with it where the control surface had 0.31 m).
  const std::size_t points = d.settings.refine ? d.settings.max_control_points : d.settings.control_points;
  if (d.skin_method_auto) d.settings.skin_method = deform::preferredSkinMethod(points, d.settings.k_nearest);
}

std::optional<DeformationConfig> deformationPreset(const std::string& name) {
  // The presets are levels of the budget's table (deformation_budget.cpp), chosen from the measured front
  // (docs/TRADEOFF.md): the error against the reference is set by the control points; substeps,
  // iterations and K beyond these buy almost nothing.
  const DeformationLevel* level = deformationLevel(name);
  if (!level) return std::nullopt;
  DeformationConfig d;
  d.preset = name;
  applyLevel(*level, d.settings);  // the rest: vehicle's calibrated defaults
  resolveSkinMethod(d);            // auto: the skin measured best at the preset's control points
  return d;
}

Override parseOverride(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw deform::InputError("--set: expected key.path=value (got '" + text + "')");
  }
  return {text.substr(0, eq), text.substr(eq + 1)};
}

json parseRefusingDuplicates(const std::string& text, const std::string& source);

namespace {

/// Well-formed UTF-8 (RFC 3629: no overlong forms, no surrogates, nothing above U+10FFFF), as JSON text
/// must be. A file's strings are checked by the parser; a --set key or bare word is not.
bool validUtf8(const std::string& text) {
  const auto* p = reinterpret_cast<const unsigned char*>(text.data());
  const unsigned char* end = p + text.size();
  while (p < end) {
    const unsigned char c = *p;
    int follow = 0;
    unsigned char low = 0x80, high = 0xBF;  // the range of the first continuation byte
    if (c < 0x80) {
      ++p;
      continue;
    } else if (c >= 0xC2 && c <= 0xDF) {
      follow = 1;
    } else if (c >= 0xE0 && c <= 0xEF) {
      follow = 2;
      if (c == 0xE0) low = 0xA0;
      if (c == 0xED) high = 0x9F;
    } else if (c >= 0xF0 && c <= 0xF4) {
      follow = 3;
      if (c == 0xF0) low = 0x90;
      if (c == 0xF4) high = 0x8F;
    } else {
      return false;
    }
    if (end - p <= follow) return false;
    if (p[1] < low || p[1] > high) return false;
    for (int k = 2; k <= follow; ++k)
      if (p[k] < 0x80 || p[k] > 0xBF) return false;
    p += follow + 1;
  }
  return true;
}

}  // namespace

void applyOverride(json& document, const Override& override) {
  if (!validUtf8(override.path) || !validUtf8(override.value))
    throw deform::InputError("--set: the key or the value is not valid UTF-8 text");
  // "obstacles[0].x" -> "obstacles.0.x"
  std::string path = override.path;
  std::replace(path.begin(), path.end(), '[', '.');
  path.erase(std::remove(path.begin(), path.end(), ']'), path.end());
  std::vector<std::string> parts;
  std::istringstream stream(path);
  for (std::string part; std::getline(stream, part, '.');) {
    if (part.empty()) throw deform::InputError("--set " + override.path + ": empty key in the path");
    parts.push_back(part);
  }
  if (parts.empty()) throw deform::InputError("--set: empty key path");
  // The scene's cars are under one of the two keys: a --set for the other would add it, and the scene
  // would then be refused for having both, with no word about the --set.
  if (document.is_object()) {
    if (parts[0] == "vehicle" && !document.contains("vehicle") && document.contains("vehicles"))
      throw deform::InputError(
          "--set " + override.path + ": this scene lists its cars under vehicles: set vehicles[0]." +
          (parts.size() > 1 ? override.path.substr(override.path.find('.') + 1) : "...") +
          " (and the same for each car)");
    if (parts[0] == "vehicles" && !document.contains("vehicles") && document.contains("vehicle")) {
      // vehicles[0].mass_kg -> vehicle.mass_kg
      const std::size_t after = override.path.find("].");
      throw deform::InputError(
          "--set " + override.path + ": this scene has one car, under vehicle: set vehicle." +
          (after != std::string::npos ? override.path.substr(after + 2) : "...") + " instead");
    }
  }
  json value;
  try {
    value = parseRefusingDuplicates(override.value, "--set " + override.path);
  } catch (const json::parse_error&) {
    value = override.value;  // a bare word: a string
  }
  json* node = &document;
  std::string walked;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::string& part = parts[i];
    const bool last = i + 1 == parts.size();
    walked += (walked.empty() ? "" : ".") + part;
    if (node->is_array()) {
      const bool digits = std::all_of(part.begin(), part.end(), [](char c) { return c >= '0' && c <= '9'; });
      const std::size_t index = digits && part.size() < 9 ? std::stoul(part) : node->size() + 1;
      if (last && index == node->size()) {  // one past the end appends
        node->push_back(value);
        return;
      }
      if (index >= node->size()) {
        throw deform::InputError("--set " + override.path + ": " + walked + ": no such item (the array has " +
                                 std::to_string(node->size()) + ")");
      }
      node = &(*node)[index];
    } else if (node->is_object()) {
      if (last) {
        (*node)[part] = value;
        return;
      }
      if (!node->contains(part)) (*node)[part] = json::object();
      node = &(*node)[part];
    } else {
      throw deform::InputError("--set " + override.path + ": " + walked + ": the value above is " +
                               detail::typeName(*node) + ", not an object");
    }
    if (last) *node = value;
  }
}

std::string shippedScenesDir() {
#ifdef DEFORM_SCENES_DIR
  if (deform::isDirectory(DEFORM_SCENES_DIR)) return DEFORM_SCENES_DIR;
#endif
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec && deform::isDirectory(exe.parent_path() / "scenes"))
    return (exe.parent_path() / "scenes").string();
  return "scenes";
}

std::vector<std::string> shippedSceneNames() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(shippedScenesDir(), ec)) {
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

/// json::parse, but a key given twice in one object is refused, naming the file and the key's path (the
/// standard leaves duplicates undefined and nlohmann keeps the last silently).
json parseRefusingDuplicates(const std::string& text, const std::string& source) {
  struct Frame {
    bool array = false;
    std::size_t index = 0;
    std::set<std::string> keys;
    std::string key;
  };
  std::vector<Frame> frames;
  auto pathOf = [&frames](const std::string& last) {
    std::string path;
    for (std::size_t i = 0; i + 1 < frames.size(); ++i) {
      const Frame& f = frames[i];
      path += f.array ? "[" + std::to_string(f.index) + "]" : (path.empty() ? "" : ".") + f.key;
    }
    return path + (path.empty() ? "" : ".") + last;
  };
  auto childEnded = [&frames] {
    if (!frames.empty() && frames.back().array) ++frames.back().index;
  };
  const json::parser_callback_t check = [&](int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
        frames.push_back({});
        break;
      case json::parse_event_t::array_start:
        frames.push_back({true, 0, {}, {}});
        break;
      case json::parse_event_t::key: {
        const std::string key = parsed.get<std::string>();
        if (!frames.back().keys.insert(key).second)
          throw deform::InputError(source + ": " + pathOf(key) + ": key given twice (give each key once)");
        frames.back().key = key;
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames.pop_back();
        childEnded();
        break;
      case json::parse_event_t::value:
        childEnded();
        break;
    }
    return true;
  };
  try {
    return json::parse(text, check);
  } catch (const json::out_of_range& e) {
    // A number beyond a double ("1e999"): nlohmann throws out_of_range (406), not parse_error, so without
    // this it escaped as an internal failure (exit 1; tests/fuzz/regressions/scene/).
    const std::string what = e.what();
    const std::size_t quote = what.find('\'');
    const std::string number = quote == std::string::npos ? what : what.substr(quote);
    throw deform::InputError(source + ": a number too large for a double: " + number);
  }
}

std::string resolveScenePath(const std::string& name_or_path) {
  if (deform::isRegularFile(name_or_path)) return name_or_path;
  const bool bare_name = name_or_path.find('/') == std::string::npos && !name_or_path.empty();
  if (bare_name) {
    fs::path shipped = fs::path(shippedScenesDir()) / name_or_path;
    if (shipped.extension() != ".json") shipped += ".json";
    if (deform::isRegularFile(shipped)) return shipped.string();
  }
  std::string names;
  for (const std::string& n : shippedSceneNames()) names += (names.empty() ? "" : ", ") + n;
  throw deform::InputError(name_or_path + ": no such scene file or shipped scene (shipped: " + names + ")");
}

SceneConfig parseScene(const json& document, const std::string& source, const std::string& base_dir) {
  JsonObject top(document, "", source);
  SceneConfig scene;
  scene.source = source;
  nlohmann::json physics = document;
  if (physics.is_object())
    for (const char* key : {"camera", "outputs", "description", "$schema", "threads"}) physics.erase(key);
  const std::string resolved = physics.dump();
  scene.settings_hash = vehicle::fnv1a(resolved.data(), resolved.size());
  scene.name = top.string("name", fs::path(source).stem().string());
  scene.description = top.string("description", "");
  top.string("$schema", "");  // editors' schema hint, ignored
  scene.duration_s = top.number("duration_s", std::nullopt, 1e-3, 1e5);
  scene.physics_hz = top.number("physics_hz", std::nullopt, 15, 20000);
  if (top.has("threads")) scene.threads = static_cast<int>(top.integer("threads", std::nullopt, 1, 1024));
  if (top.has("deformation_budget_ms"))
    scene.deformation_budget_ms = top.number("deformation_budget_ms", std::nullopt, 0, 1e6);
  scene.gravity_mps2 = top.number("gravity_mps2", 9.81, 0, 100);
  scene.ground = top.boolean("ground", true);
  scene.ground_friction = top.number("ground_friction", 1.0, 0, 10);
  if (top.has("vehicle") && top.has("vehicles")) {
    top.fail("vehicles", "give either vehicle (one car) or vehicles (a list), not both");
  }
  if (top.has("vehicle")) {
    JsonObject v = *top.object("vehicle", true);
    scene.vehicles.push_back(parseVehicle(v, 0, base_dir));
  } else {
    std::vector<JsonObject> list = top.objects("vehicles");
    if (list.empty()) top.fail("vehicle", "missing (required: vehicle, or vehicles with at least one car)");
    for (std::size_t i = 0; i < list.size(); ++i)
      scene.vehicles.push_back(parseVehicle(list[i], i, base_dir));
  }
  std::vector<JsonObject> obstacles = top.objects("obstacles");
  for (std::size_t i = 0; i < obstacles.size(); ++i) {
    scene.obstacles.push_back(parseObstacle(obstacles[i], i, base_dir));
  }
  scene.camera = parseCamera(top.object("camera"), scene.vehicles.size());
  scene.outputs = parseOutputs(top.object("outputs"));
  top.finish();
  return scene;
}

SceneConfig loadScene(const std::string& name_or_path, const std::vector<Override>& overrides) {
  const std::string path = resolveScenePath(name_or_path);
  return parseSceneText(readText(path), path, overrides, fs::path(path).parent_path().string());
}

SceneConfig parseSceneText(const std::string& text, const std::string& path,
                           const std::vector<Override>& overrides, const std::string& base_dir) {
  json document;
  try {
    document = parseRefusingDuplicates(text, path);
  } catch (const json::parse_error& e) {
    throw deform::InputError(path + ": not valid JSON at " + lineColumn(text, e.byte > 0 ? e.byte - 1 : 0));
  }
  for (const Override& o : overrides) applyOverride(document, o);
  try {
    return parseScene(document, path, base_dir);
  } catch (const deform::InputError& e) {
    // Name the override when the refused key is one that --set gave.
    const std::string message = e.what();
    for (const Override& o : overrides) {
      std::string dotted = o.path;
      std::replace(dotted.begin(), dotted.end(), '[', '.');
      dotted.erase(std::remove(dotted.begin(), dotted.end(), ']'), dotted.end());
      std::string shown = message;
      std::replace(shown.begin(), shown.end(), '[', '.');
      shown.erase(std::remove(shown.begin(), shown.end(), ']'), shown.end());
      if (shown.find(": " + dotted + ":") != std::string::npos) {
        throw deform::InputError(message + " (from --set " + o.path + "=" + o.value + ")");
      }
    }
    throw;
  }
}

}  // namespace scenes

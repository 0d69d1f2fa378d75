#include "sweep/sweep_case.hpp"

#include "build_version.hpp"
#include "grid/grid_sweep.hpp"
#include "stress/stress_sweep.hpp"
#include "tradeoff/tradeoff.hpp"

#include <scenes/scene_file.hpp>
#include <scenes/scene_run.hpp>

#include <deform/error.hpp>

#include <array>
#include <chrono>
#include <cstring>
#include <exception>

namespace sandbox {
namespace {

constexpr char kBase64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

}  // namespace

nlohmann::json measureCrash(const std::string& scene, const std::vector<std::string>& overrides) {
  std::vector<scenes::Override> parsed;
  for (const std::string& o : overrides) parsed.push_back(scenes::parseOverride(o));
  const scenes::SceneConfig config = scenes::loadScene(scene, parsed);
  scenes::SceneRun run(config);
  run.runToEnd();
  const vehicle::CrashMetrics m = run.simulation().metrics(run.carId(0));
  scenes::SkinCache skins;
  const vehicle::CrushStations surface = run.surfaceCrush(0, skins);
  return {{"scene_name", config.name},
          {"surface_residual_crush_m", surface.mean_m},
          {"surface_crush_profile_m", scenes::profileJson(surface.profile_m)},
          {"surface_crush_height_m", surface.height_m},
          {"impact_speed_mps", m.impact_speed_mps},
          {"residual_crush_m", m.residual_crush_m},
          {"max_residual_crush_m", m.max_residual_crush_m},
          {"crush_profile_m", scenes::profileJson(m.crush_profile_m)},
          {"crush_height_m", m.crush_height_m},
          {"max_dynamic_crush_m", m.max_dynamic_crush_m},
          {"max_dent_m", m.max_dent_m},
          {"crushed_volume_m3", m.crushed_volume_m3},
          {"restitution", m.restitution},
          {"plastic_work_J", m.energy.plastic_work_J},
          {"kinetic_initial_J", m.energy.kinetic_initial_J},
          {"contact_work_J", m.energy.contact_work_J},
          {"diverged", m.diverged},
          {"state_hash", scenes::hashHex(run.stateHash())},
          {"physics_ms", run.times().physics_ms()},
          {"deform_ms", run.times().deformation_ms()}};
}

nlohmann::json measureCase(const SweepCase& sweep_case) {
  if (sweep_case.measure == "tradeoff") return measureTradeoffCase(sweep_case.scene, sweep_case.overrides);
  if (sweep_case.measure == "crash") return measureCrash(sweep_case.scene, sweep_case.overrides);
  if (sweep_case.measure == "grid") return measureGridCase(sweep_case);
  if (sweep_case.measure == "stress") {
    const auto group = sweep_case.labels.find("group");
    if (group == sweep_case.labels.end() || !group->is_string())
      throw deform::InputError("case " + sweep_case.id + ": labels.group: missing");
    return measureStressGroup(group->get<std::string>(), sweep_case.labels.value("quick", false));
  }
  throw deform::InputError("case " + sweep_case.id + ": unknown measure '" + sweep_case.measure + "'");
}

nlohmann::json runCase(const SweepCase& sweep_case, const std::string& plan_id) {
  nlohmann::json result = {{"case", sweep_case.id}, {"plan_id", plan_id}, {"status", "done"},
                           {"exit_code", 0},        {"error", ""},        {"version", buildVersion()},
                           {"scene_hash", ""},      {"seconds", 0.0},     {"measured", nullptr}};
  const auto start = std::chrono::steady_clock::now();
  const auto fail = [&](int code, const std::string& message) {
    result["status"] = "failed";
    result["exit_code"] = code;
    result["error"] = message;
  };
  try {
    if (!sweep_case.scene.empty()) result["scene_hash"] = sceneFileHash(sweep_case.scene);
    result["measured"] = measureCase(sweep_case);
  } catch (const deform::InputError& e) {
    fail(2, e.what());
  } catch (const std::exception& e) {
    fail(1, e.what());
  }
  result["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

std::string encodePoints(const std::vector<Eigen::Vector3f>& points) {
  std::vector<unsigned char> bytes(points.size() * 12);
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      uint32_t bits;
      std::memcpy(&bits, &points[i][k], 4);
      for (int b = 0; b < 4; ++b)
        bytes[12 * i + 4 * static_cast<std::size_t>(k) + b] =
            static_cast<unsigned char>((bits >> (8 * b)) & 0xff);
    }
  }
  std::string text;
  text.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t n = (uint32_t{bytes[i]} << 16) |
                       (i + 1 < bytes.size() ? uint32_t{bytes[i + 1]} << 8 : 0u) |
                       (i + 2 < bytes.size() ? uint32_t{bytes[i + 2]} : 0u);
    text += kBase64[(n >> 18) & 63];
    text += kBase64[(n >> 12) & 63];
    text += i + 1 < bytes.size() ? kBase64[(n >> 6) & 63] : '=';
    text += i + 2 < bytes.size() ? kBase64[n & 63] : '=';
  }
  return text;
}

double measuredNumber(const nlohmann::json& measured, const std::string& name, const std::string& what) {
  const auto it = measured.find(name);
  if (it == measured.end() || !it->is_number())
    throw deform::InputError(what + ": measured." + name + ": missing or not a number");
  return it->get<double>();
}

std::vector<Eigen::Vector3f> decodePoints(const std::string& text, const std::string& what) {
  std::array<int, 256> value;
  value.fill(-1);
  for (int i = 0; i < 64; ++i) value[static_cast<unsigned char>(kBase64[i])] = i;
  if (text.size() % 4 != 0) throw deform::InputError(what + ": not base64 (length)");
  std::vector<unsigned char> bytes;
  bytes.reserve(text.size() / 4 * 3);
  for (std::size_t i = 0; i < text.size(); i += 4) {
    uint32_t n = 0;
    int pad = 0;
    for (std::size_t k = 0; k < 4; ++k) {
      const char c = text[i + k];
      const bool last_group = i + 4 == text.size();
      if (c == '=' && last_group && k >= 2) {
        ++pad;
        n <<= 6;
        continue;
      }
      const int v = value[static_cast<unsigned char>(c)];
      if (v < 0 || pad > 0) throw deform::InputError(what + ": not base64");
      n = (n << 6) | static_cast<uint32_t>(v);
    }
    bytes.push_back(static_cast<unsigned char>((n >> 16) & 0xff));
    if (pad < 2) bytes.push_back(static_cast<unsigned char>((n >> 8) & 0xff));
    if (pad < 1) bytes.push_back(static_cast<unsigned char>(n & 0xff));
  }
  if (bytes.size() % 12 != 0) throw deform::InputError(what + ": not a whole number of points");
  std::vector<Eigen::Vector3f> points(bytes.size() / 12);
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      uint32_t bits = 0;
      for (int b = 0; b < 4; ++b)
        bits |= uint32_t{bytes[12 * i + 4 * static_cast<std::size_t>(k) + b]} << (8 * b);
      std::memcpy(&points[i][k], &bits, 4);
    }
  }
  return points;
}

}  // namespace sandbox

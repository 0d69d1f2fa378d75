// A scene run's state file (scenes/README.md, "Save and resume"): written at a simulated time, read back
// into a run built from the same scene and settings, which then continues bit for bit as the
// uninterrupted run would.
//
// Layout (little-endian): "DFMSTATE" (8 bytes), format version (u64), payload length (u64), FNV-1a 64 of
// the payload (u64), then the payload: scene name, scene source (for messages), settings_hash, steps,
// time, advance()'s frame clock, each car's speed controller, and vehicle::Simulation::saveState.
#include <scenes/scene_run.hpp>

#include <vehicle/state_io.hpp>

#include <deform/error.hpp>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>

namespace scenes {
namespace {

constexpr char kMagic[8] = {'D', 'F', 'M', 'S', 'T', 'A', 'T', 'E'};
constexpr uint64_t kVersion = 5;  // 2: the crush coupling's obstacle work; 3: the visual coupling's ghost;
                                  // 4: the energy watch; 5: each body's refinement (its splits)
constexpr std::size_t kHeaderBytes = 32;

uint64_t readU64(std::span<const uint8_t> bytes, std::size_t at) {
  uint64_t value = 0;
  for (std::size_t i = 0; i < 8; ++i) value |= static_cast<uint64_t>(bytes[at + i]) << (8 * i);
  return value;
}

}  // namespace

std::vector<uint8_t> SceneRun::stateBytes(bool for_hash) const {
  vehicle::StateWriter out(for_hash);
  out.real(frame_time_s_);
  out.u64(cars_.size());
  for (const Car& car : cars_) out.real(car.driver.controller().integral_m());
  simulation_->saveState(out);
  return out.take();
}

uint64_t SceneRun::stateHash() const {
  const std::vector<uint8_t> bytes = stateBytes(true);
  return vehicle::fnv1a(bytes.data(), bytes.size());
}

std::vector<uint8_t> SceneRun::stateFile() const {
  vehicle::StateWriter payload;
  payload.text(scene_.name);
  payload.text(scene_.source);
  payload.u64(scene_.settings_hash);
  payload.u64(steps());
  payload.real(time_s());
  payload.blob(stateBytes(false));
  const std::vector<uint8_t>& body = payload.bytes();
  vehicle::StateWriter file;
  file.raw(kMagic, sizeof kMagic);
  file.u64(kVersion);
  file.u64(body.size());
  file.u64(vehicle::fnv1a(body.data(), body.size()));
  file.raw(body.data(), body.size());
  return file.take();
}

void SceneRun::saveState(const std::string& path) const {
  const std::vector<uint8_t> bytes = stateFile();
  writeFileAtomically(path, std::string(bytes.begin(), bytes.end()));
}

void SceneRun::restoreState(std::span<const uint8_t> bytes, const std::string& name) {
  auto refuse = [&name](const std::string& why) { throw deform::InputError(name + ": " + why); };
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    refuse("not a sandbox state file (no DFMSTATE mark)");
  if (bytes.size() < kHeaderBytes)
    refuse("truncated (" + std::to_string(bytes.size()) + " bytes, shorter than the header)");
  const uint64_t version = readU64(bytes, 8), length = readU64(bytes, 16), checksum = readU64(bytes, 24);
  if (version > kVersion)
    refuse("written by a newer format version (" + std::to_string(version) + "; this build reads " +
           std::to_string(kVersion) + ")");
  if (version != kVersion) refuse("unknown format version " + std::to_string(version));
  const std::size_t found = bytes.size() - kHeaderBytes;
  if (length > found)
    refuse("truncated (" + std::to_string(found) + " of " + std::to_string(length) + " payload bytes)");
  if (length < found) refuse("corrupted (" + std::to_string(found - length) + " bytes after the payload)");
  const std::span<const uint8_t> payload = bytes.subspan(kHeaderBytes);
  if (vehicle::fnv1a(payload.data(), payload.size()) != checksum) refuse("corrupted (checksum mismatch)");

  vehicle::StateReader in(payload, name + ": corrupted");
  const std::string scene_name = in.text(), scene_source = in.text();
  const uint64_t settings_hash = in.u64(), saved_steps = in.u64();
  const double saved_time_s = in.real();
  if (scene_name != scene_.name)
    refuse("a state of scene '" + scene_name + "' (" + scene_source + "), not of '" + scene_.name + "'");
  if (settings_hash != scene_.settings_hash)
    refuse("saved with other settings of scene '" + scene_name +
           "' (its keys or --set values differ from this run's)");
  const std::span<const uint8_t> state = in.blob();
  in.expect(in.done(), "bytes after the state");

  vehicle::StateReader s(state, name + ": corrupted");
  frame_time_s_ = s.real();
  s.expect(s.u64() == cars_.size(), "car count does not match the scene");
  std::vector<double> integrals;
  for (std::size_t i = 0; i < cars_.size(); ++i) integrals.push_back(s.real());
  simulation_->restoreState(s);
  s.expect(s.done(), "bytes after the state");
  for (std::size_t i = 0; i < cars_.size(); ++i) cars_[i].driver.controller().setIntegral_m(integrals[i]);
  if (steps() != saved_steps || time_s() != saved_time_s) refuse("corrupted (step counter or time disagree)");
  steps_at_start_ = saved_steps;
}

void SceneRun::restoreState(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw deform::InputError(path + ": cannot read the state file");
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  if (file.bad()) throw deform::InputError(path + ": cannot read the state file");
  restoreState(bytes, path);
}

std::string stateFileSceneSource(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw deform::InputError(path + ": cannot read the state file");
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  if (bytes.size() < kHeaderBytes || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    throw deform::InputError(path + ": not a sandbox state file (no DFMSTATE mark)");
  vehicle::StateReader in(std::span<const uint8_t>(bytes).subspan(kHeaderBytes), path + ": corrupted");
  in.text();  // the scene's name
  return in.text();
}

}  // namespace scenes

// Snapshots of a body's state: the rest state, a hash, bit-exact save and restore.
#include "byte_io.hpp"

#include <deform/body_state.hpp>
#include <deform/error.hpp>

namespace deform {
namespace {

constexpr uint32_t kSnapshotMagic = 0x54534644;  // "DFST"
constexpr uint32_t kSnapshotVersion = 2;

/// Every field in a fixed order, handed to `sink(pointer, bytes)`; shared by the hash and the snapshot.
template <class Sink>
void visitState(const BodyState& s, Sink&& sink) {
  sink(s.positions_m.data(), s.positions_m.size() * sizeof(Eigen::Vector3d));
  sink(s.velocities_mps.data(), s.velocities_mps.size() * sizeof(Eigen::Vector3d));
  sink(s.edge_rest_m.data(), s.edge_rest_m.size() * sizeof(double));
  sink(s.spoke_rest_m.data(), s.spoke_rest_m.size() * sizeof(double));
  sink(s.bend_rest_m.data(), s.bend_rest_m.size() * sizeof(double));
  sink(s.column_rest_m.data(), s.column_rest_m.size() * sizeof(Eigen::Vector3d));
  sink(&s.plastic_work_J, sizeof(double));
  sink(&s.time_s, sizeof(double));
  sink(&s.sleep_timer_s, sizeof(double));
  const uint8_t sleeping = s.sleeping ? 1 : 0;
  sink(&sleeping, 1);
  sink(s.sleep_load_mps2.data(), 3 * sizeof(double));
  sink(s.sleep_angular_velocity_radps.data(), 3 * sizeof(double));
  sink(s.sleep_angular_acceleration_radps2.data(), 3 * sizeof(double));
}

}  // namespace

static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double), "Vector3d must be three packed doubles");

BodyState restState(const BodySettings& settings) {
  BodyState s;
  s.positions_m = settings.rest_positions_m;
  s.velocities_mps.assign(settings.pointCount(), Eigen::Vector3d::Zero());
  s.edge_rest_m = settings.edge_rest_m;
  s.spoke_rest_m = settings.spoke_rest_m;
  s.bend_rest_m = settings.bend_rest_m;
  s.column_rest_m = settings.rest_positions_m;
  return s;
}

uint64_t hashState(const BodyState& state) {
  uint64_t hash = 14695981039346656037ULL;  // FNV-1a 64
  visitState(state, [&hash](const void* data, std::size_t size) {
    const auto* p = static_cast<const uint8_t*>(data);
    for (std::size_t i = 0; i < size; ++i) hash = (hash ^ p[i]) * 1099511628211ULL;
  });
  return hash;
}

std::vector<uint8_t> saveState(const BodyState& state) {
  std::vector<uint8_t> out;
  bytes::putVarint(out, kSnapshotMagic);
  bytes::putVarint(out, kSnapshotVersion);
  bytes::putVarint(out, state.positions_m.size());
  bytes::putVarint(out, state.edge_rest_m.size());
  bytes::putVarint(out, state.spoke_rest_m.size());
  bytes::putVarint(out, state.bend_rest_m.size());
  visitState(state, [&out](const void* data, std::size_t size) { bytes::putRaw(out, data, size); });
  return out;
}

BodyState restoreState(const BodySettings& settings, std::span<const uint8_t> data) {
  bytes::Reader in(data, "state snapshot");
  if (in.varint() != kSnapshotMagic) throw InputError("state snapshot: not a deform state snapshot");
  if (in.varint() != kSnapshotVersion) throw InputError("state snapshot: unknown version");
  const uint64_t points = in.varint(), edges = in.varint(), spokes = in.varint(), bends = in.varint();
  if (points != settings.pointCount() || edges != settings.edges.size() || spokes != settings.spokes.size() ||
      bends != settings.bends.size())
    throw InputError("state snapshot: point or constraint counts do not match the body");
  BodyState s = restState(settings);
  uint8_t sleeping = 0;
  // The same visit order as saveState; each field is read into place.
  auto read = [&in](void* target, std::size_t size) { in.raw(target, size); };
  read(s.positions_m.data(), s.positions_m.size() * sizeof(Eigen::Vector3d));
  read(s.velocities_mps.data(), s.velocities_mps.size() * sizeof(Eigen::Vector3d));
  read(s.edge_rest_m.data(), s.edge_rest_m.size() * sizeof(double));
  read(s.spoke_rest_m.data(), s.spoke_rest_m.size() * sizeof(double));
  read(s.bend_rest_m.data(), s.bend_rest_m.size() * sizeof(double));
  read(s.column_rest_m.data(), s.column_rest_m.size() * sizeof(Eigen::Vector3d));
  read(&s.plastic_work_J, sizeof(double));
  read(&s.time_s, sizeof(double));
  read(&s.sleep_timer_s, sizeof(double));
  read(&sleeping, 1);
  read(s.sleep_load_mps2.data(), 3 * sizeof(double));
  read(s.sleep_angular_velocity_radps.data(), 3 * sizeof(double));
  read(s.sleep_angular_acceleration_radps2.data(), 3 * sizeof(double));
  s.sleeping = sleeping != 0;
  if (!in.done()) throw InputError("state snapshot: trailing bytes");
  return s;
}

}  // namespace deform

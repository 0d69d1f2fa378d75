// Compact permanent damage: sparse, quantised deltas from the undamaged body as varints.
#include "byte_io.hpp"

#include <deform/damage.hpp>
#include <deform/error.hpp>

#include <cmath>

namespace deform {
namespace {

constexpr uint32_t kDamageMagic = 0x4d444644;  // "DFDM"
constexpr uint32_t kDamageVersion = 2;         // 2: the crush columns' rest places

int64_t quantise(double delta_m) {
  return std::llround(delta_m / kDamageQuantum_m);
}

void putRestDeltas(std::vector<uint8_t>& out, const std::vector<double>& rest,
                   const std::vector<double>& original) {
  std::vector<std::pair<uint64_t, int64_t>> changed;
  for (std::size_t k = 0; k < rest.size(); ++k)
    if (const int64_t q = quantise(rest[k] - original[k]); q != 0) changed.emplace_back(k, q);
  bytes::putVarint(out, changed.size());
  uint64_t next = 0;
  for (const auto& [k, q] : changed) {
    bytes::putVarint(out, k - next);  // gap from the previous index
    bytes::putSigned(out, q);
    next = k + 1;
  }
}

void readRestDeltas(bytes::Reader& in, std::vector<double>& rest, const std::vector<double>& original) {
  const uint64_t count = in.varint();
  uint64_t next = 0;
  for (uint64_t j = 0; j < count; ++j) {
    const uint64_t k = next + in.varint();
    if (k >= rest.size()) throw InputError("damage record: rest-length index out of range");
    rest[k] = original[k] + static_cast<double>(in.signedVarint()) * kDamageQuantum_m;
    next = k + 1;
  }
}

/// Sparse quantised deltas of 3-vectors (control points, the crush columns' rest places) from `original`.
void putPlaceDeltas(std::vector<uint8_t>& out, const std::vector<Eigen::Vector3d>& place,
                    const std::vector<Eigen::Vector3d>& original) {
  std::vector<std::pair<uint64_t, Eigen::Matrix<int64_t, 3, 1>>> moved;
  for (std::size_t i = 0; i < place.size(); ++i) {
    const Eigen::Vector3d delta = place[i] - original[i];
    const Eigen::Matrix<int64_t, 3, 1> q(quantise(delta.x()), quantise(delta.y()), quantise(delta.z()));
    if (q.any()) moved.emplace_back(i, q);
  }
  bytes::putVarint(out, moved.size());
  uint64_t next = 0;
  for (const auto& [i, q] : moved) {
    bytes::putVarint(out, i - next);
    for (int a = 0; a < 3; ++a) bytes::putSigned(out, q[a]);
    next = i + 1;
  }
}

void readPlaceDeltas(bytes::Reader& in, std::vector<Eigen::Vector3d>& place,
                     const std::vector<Eigen::Vector3d>& original) {
  const uint64_t count = in.varint();
  uint64_t next = 0;
  for (uint64_t j = 0; j < count; ++j) {
    const uint64_t i = next + in.varint();
    if (i >= place.size()) throw InputError("damage record: point index out of range");
    for (int a = 0; a < 3; ++a)
      place[i][a] = original[i][a] + static_cast<double>(in.signedVarint()) * kDamageQuantum_m;
    next = i + 1;
  }
}

}  // namespace

std::vector<uint8_t> encodeDamage(const BodySettings& settings, const BodyState& state) {
  std::vector<uint8_t> out;
  bytes::putVarint(out, kDamageMagic);
  bytes::putVarint(out, kDamageVersion);
  bytes::putVarint(out, settings.pointCount());
  bytes::putVarint(out, settings.edges.size());
  bytes::putVarint(out, settings.spokes.size());
  bytes::putVarint(out, settings.bends.size());
  bytes::putDouble(out, state.plastic_work_J);

  putPlaceDeltas(out, state.positions_m, settings.rest_positions_m);
  putRestDeltas(out, state.edge_rest_m, settings.edge_rest_m);
  putRestDeltas(out, state.spoke_rest_m, settings.spoke_rest_m);
  putRestDeltas(out, state.bend_rest_m, settings.bend_rest_m);
  putPlaceDeltas(out, state.column_rest_m, settings.rest_positions_m);
  return out;
}

BodyState decodeDamage(const BodySettings& settings, std::span<const uint8_t> data) {
  bytes::Reader in(data, "damage record");
  if (in.varint() != kDamageMagic) throw InputError("damage record: not a deform damage record");
  if (in.varint() != kDamageVersion) throw InputError("damage record: unknown version");
  if (in.varint() != settings.pointCount() || in.varint() != settings.edges.size() ||
      in.varint() != settings.spokes.size() || in.varint() != settings.bends.size())
    throw InputError("damage record: point or constraint counts do not match the body");
  BodyState state = restState(settings);
  state.plastic_work_J = in.real();
  readPlaceDeltas(in, state.positions_m, settings.rest_positions_m);
  readRestDeltas(in, state.edge_rest_m, settings.edge_rest_m);
  readRestDeltas(in, state.spoke_rest_m, settings.spoke_rest_m);
  readRestDeltas(in, state.bend_rest_m, settings.bend_rest_m);
  readPlaceDeltas(in, state.column_rest_m, settings.rest_positions_m);
  if (!in.done()) throw InputError("damage record: trailing bytes");
  return state;
}

}  // namespace deform

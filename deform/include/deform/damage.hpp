#pragma once
// The permanent damage of a body in compact form, for saving a damaged car or sending it over a
// network: control-point position deltas and rest-length deltas from the undamaged body, quantised to
// 0.1 mm, only those that are not zero, as variable-length integers.
#include <deform/body_settings.hpp>
#include <deform/body_state.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace deform {

/// Quantum of the damage record [m].
inline constexpr double kDamageQuantum_m = 1e-4;

/// Encodes the damage of `state` (positions and rest lengths against `settings`, plus the plastic work).
std::vector<uint8_t> encodeDamage(const BodySettings& settings, const BodyState& state);

/// A body at rest with the damage applied: every position and rest length within half a quantum of
/// the encoded one, velocities zero. Throws InputError when the bytes are not a damage record for
/// `settings`.
BodyState decodeDamage(const BodySettings& settings, std::span<const uint8_t> bytes);

}  // namespace deform

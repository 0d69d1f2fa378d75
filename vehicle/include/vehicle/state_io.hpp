#pragma once
// Bytes of a saved simulation state (World, Simulation, the scene runner): doubles copied bit for bit
// (the platform's IEEE 754 layout), integers as fixed-width little-endian words. Not a format of its own:
// the state file that carries these bytes (scenes/README.md) adds the magic, version, length and checksum.
#include <deform/error.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

namespace vehicle {

/// Appends values to a byte buffer.
class StateWriter {
 public:
  /// A writer for a state hash rather than a state file: what only reflects the scene's fixed make-up
  /// (the obstacle count, where static geoms sit in the collision order) is left out, so obstacles that
  /// never take part change no hash.
  explicit StateWriter(bool for_hash = false) : for_hash_(for_hash) {}
  bool forHash() const { return for_hash_; }
  void raw(const void* data, std::size_t size) {
    if (size == 0) return;
    const std::size_t at = bytes_.size();
    bytes_.resize(at + size);
    std::memcpy(bytes_.data() + at, data, size);
  }
  void real(double value) { raw(&value, sizeof value); }
  void u64(uint64_t value) {
    for (int i = 0; i < 8; ++i) bytes_.push_back(static_cast<uint8_t>(value >> (8 * i)));
  }
  void flag(bool value) { bytes_.push_back(value ? 1 : 0); }
  void vec(const Eigen::Vector3d& v) {
    for (int i = 0; i < 3; ++i) real(v[i]);
  }
  void text(const std::string& s) {
    u64(s.size());
    raw(s.data(), s.size());
  }
  void blob(std::span<const uint8_t> data) {
    u64(data.size());
    raw(data.data(), data.size());
  }
  const std::vector<uint8_t>& bytes() const { return bytes_; }
  std::vector<uint8_t> take() { return std::move(bytes_); }

 private:
  bool for_hash_ = false;
  std::vector<uint8_t> bytes_;
};

/// Reads what StateWriter wrote, in the same order. Throws deform::InputError "<what>: truncated" when the
/// bytes run out and "<what>: <field> ..." from expect().
class StateReader {
 public:
  StateReader(std::span<const uint8_t> data, std::string what) : data_(data), what_(std::move(what)) {}

  void raw(void* out, std::size_t size) {
    if (size == 0) return;  // an empty vector's data() may be null, which memcpy may not be given
    need(size);
    std::memcpy(out, data_.data() + at_, size);
    at_ += size;
  }
  double real() {
    double value;
    raw(&value, sizeof value);
    return value;
  }
  uint64_t u64() {
    need(8);
    uint64_t value = 0;
    for (int i = 0; i < 8; ++i)
      value |= static_cast<uint64_t>(data_[at_ + static_cast<std::size_t>(i)]) << (8 * i);
    at_ += 8;
    return value;
  }
  bool flag() {
    need(1);
    const uint8_t value = data_[at_++];
    if (value > 1) fail("a flag is neither 0 nor 1");
    return value == 1;
  }
  Eigen::Vector3d vec() {
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) v[i] = real();
    return v;
  }
  /// A count of items of at least `item_bytes` each: refused when more than the bytes left could hold.
  std::size_t count(std::size_t item_bytes = 1) {
    const uint64_t n = u64();
    if (item_bytes > 0 && n > (data_.size() - at_) / item_bytes) fail("truncated");
    return static_cast<std::size_t>(n);
  }
  std::string text() {
    const std::size_t n = count();
    std::string s(n, '\0');
    raw(s.data(), n);
    return s;
  }
  std::span<const uint8_t> blob() {
    const std::size_t n = count();
    const std::span<const uint8_t> out = data_.subspan(at_, n);
    at_ += n;
    return out;
  }
  /// Throws unless `ok`, naming the field.
  void expect(bool ok, const std::string& field) const {
    if (!ok) fail(field);
  }
  [[noreturn]] void fail(const std::string& why) const { throw deform::InputError(what_ + ": " + why); }
  bool done() const { return at_ == data_.size(); }
  const std::string& what() const { return what_; }

 private:
  void need(std::size_t size) const {
    if (data_.size() - at_ < size) fail("truncated");
  }
  std::span<const uint8_t> data_;
  std::string what_;
  std::size_t at_ = 0;
};

}  // namespace vehicle

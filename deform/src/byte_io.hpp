#pragma once
// Private helpers: little byte writers and readers for snapshots and damage records. Doubles are copied
// bit for bit (the platform's IEEE 754 layout), integers as LEB128 varints.
#include <deform/error.hpp>

#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

namespace deform::bytes {

inline void putRaw(std::vector<uint8_t>& out, const void* data, std::size_t size) {
  const auto* p = static_cast<const uint8_t*>(data);
  out.insert(out.end(), p, p + size);
}

inline void putDouble(std::vector<uint8_t>& out, double value) {
  putRaw(out, &value, sizeof value);
}

inline void putVarint(std::vector<uint8_t>& out, uint64_t value) {
  while (value >= 0x80) {
    out.push_back(static_cast<uint8_t>(value | 0x80));
    value >>= 7;
  }
  out.push_back(static_cast<uint8_t>(value));
}

/// Zig-zag: small magnitudes of either sign give small varints.
inline void putSigned(std::vector<uint8_t>& out, int64_t value) {
  putVarint(out, (static_cast<uint64_t>(value) << 1) ^ static_cast<uint64_t>(value >> 63));
}

/// Reads what the writers above wrote; throws InputError naming `what` when the bytes run out.
class Reader {
 public:
  Reader(std::span<const uint8_t> data, std::string what) : data_(data), what_(std::move(what)) {}

  void raw(void* out, std::size_t size) {
    need(size);
    std::memcpy(out, data_.data() + at_, size);
    at_ += size;
  }
  double real() {
    double value;
    raw(&value, sizeof value);
    return value;
  }
  uint64_t varint() {
    uint64_t value = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      need(1);
      const uint8_t byte = data_[at_++];
      value |= static_cast<uint64_t>(byte & 0x7f) << shift;
      if (!(byte & 0x80)) return value;
    }
    throw InputError(what_ + ": malformed integer");
  }
  int64_t signedVarint() {
    const uint64_t z = varint();
    return static_cast<int64_t>(z >> 1) ^ -static_cast<int64_t>(z & 1);
  }
  bool done() const { return at_ == data_.size(); }

 private:
  void need(std::size_t size) const {
    if (data_.size() - at_ < size) throw InputError(what_ + ": truncated");
  }
  std::span<const uint8_t> data_;
  std::string what_;
  std::size_t at_ = 0;
};

}  // namespace deform::bytes

#pragma once
// A strict view of one JSON object: every key read is checked for type and range, and finish() refuses
// the keys nobody read. Messages are "<file>: <key.path>: <problem>" (deform::InputError).
#include <nlohmann/json.hpp>

#include <Eigen/Core>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace scenes::detail {

class JsonObject {
 public:
  /// Throws InputError when `value` is not an object.
  JsonObject(const nlohmann::json& value, std::string path, const std::string& source);

  const std::string& path() const { return path_; }
  /// "a.b" for key "b" of this object at "a".
  std::string keyPath(const std::string& key) const;
  bool has(const std::string& key) const;
  /// Every key of the object (in sorted order).
  std::vector<std::string> keys() const;
  /// The raw value (marks the key read); nullptr when absent.
  const nlohmann::json* raw(const std::string& key);

  /// A number in [min, max]; `fallback` when absent; InputError when required and absent.
  double number(const std::string& key, std::optional<double> fallback, double min, double max);
  /// An integer in [min, max].
  long long integer(const std::string& key, std::optional<long long> fallback, long long min, long long max);
  bool boolean(const std::string& key, std::optional<bool> fallback);
  std::string string(const std::string& key, std::optional<std::string> fallback);
  /// One of `choices`.
  std::string choice(const std::string& key, std::optional<std::string> fallback,
                     const std::vector<std::string>& choices);
  /// [x, y] or [x, y, z] (z = `z_fallback` when only two are given), each in [min, max].
  Eigen::Vector3d vector3(const std::string& key, std::optional<Eigen::Vector3d> fallback, double min,
                          double max, std::optional<double> z_fallback = std::nullopt);
  /// A child object (InputError when required and absent, or not an object).
  std::optional<JsonObject> object(const std::string& key, bool required = false);
  /// A child array of objects.
  std::vector<JsonObject> objects(const std::string& key, bool required = false);

  /// Refuses keys that were not read.
  void finish() const;

  [[noreturn]] void fail(const std::string& key, const std::string& problem) const;

 private:
  const nlohmann::json* value_;
  std::string path_;
  const std::string* source_;
  std::set<std::string> read_;
};

/// "a number", "a string", ... for messages.
std::string typeName(const nlohmann::json& value);

}  // namespace scenes::detail

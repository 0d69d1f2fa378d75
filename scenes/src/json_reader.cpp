#include "json_reader.hpp"

#include <deform/error.hpp>

#include <cmath>
#include <sstream>

namespace scenes::detail {
namespace {

std::string show(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

}  // namespace

std::string typeName(const nlohmann::json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::null:
      return "null";
    case nlohmann::json::value_t::boolean:
      return "a boolean";
    case nlohmann::json::value_t::string:
      return "a string";
    case nlohmann::json::value_t::array:
      return "an array";
    case nlohmann::json::value_t::object:
      return "an object";
    default:
      return "a number";
  }
}

JsonObject::JsonObject(const nlohmann::json& value, std::string path, const std::string& source)
    : value_(&value), path_(std::move(path)), source_(&source) {
  if (!value.is_object()) {
    throw deform::InputError(source + ": " + (path_.empty() ? std::string("(top level)") : path_) +
                             ": must be an object (got " + typeName(value) + ")");
  }
}

std::string JsonObject::keyPath(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

void JsonObject::fail(const std::string& key, const std::string& problem) const {
  const std::string where = key.empty() ? (path_.empty() ? std::string("(top level)") : path_) : keyPath(key);
  throw deform::InputError(*source_ + ": " + where + ": " + problem);
}

bool JsonObject::has(const std::string& key) const {
  return value_->contains(key);
}

std::vector<std::string> JsonObject::keys() const {
  std::vector<std::string> out;
  for (auto it = value_->begin(); it != value_->end(); ++it) out.push_back(it.key());
  return out;
}

const nlohmann::json* JsonObject::raw(const std::string& key) {
  const auto it = value_->find(key);
  if (it == value_->end()) return nullptr;
  read_.insert(key);
  return &*it;
}

double JsonObject::number(const std::string& key, std::optional<double> fallback, double min, double max) {
  const nlohmann::json* v = raw(key);
  if (!v) {
    if (!fallback) fail(key, "missing (required, a number)");
    return *fallback;
  }
  if (!v->is_number()) fail(key, "must be a number (got " + typeName(*v) + ")");
  const double x = v->get<double>();
  if (!std::isfinite(x) || x < min || x > max) {
    fail(key, "must be in [" + show(min) + ", " + show(max) + "] (got " + show(x) + ")");
  }
  return x;
}

long long JsonObject::integer(const std::string& key, std::optional<long long> fallback, long long min,
                              long long max) {
  const nlohmann::json* v = raw(key);
  if (!v) {
    if (!fallback) fail(key, "missing (required, an integer)");
    return *fallback;
  }
  if (!v->is_number_integer()) {
    fail(key, "must be an integer (got " + (v->is_number() ? v->dump() : typeName(*v)) + ")");
  }
  const long long x =
      v->is_number_unsigned() && v->get<unsigned long long>() > 1ull << 62 ? max + 1 : v->get<long long>();
  if (x < min || x > max) {
    fail(key,
         "must be in [" + std::to_string(min) + ", " + std::to_string(max) + "] (got " + v->dump() + ")");
  }
  return x;
}

bool JsonObject::boolean(const std::string& key, std::optional<bool> fallback) {
  const nlohmann::json* v = raw(key);
  if (!v) {
    if (!fallback) fail(key, "missing (required, true or false)");
    return *fallback;
  }
  if (!v->is_boolean()) fail(key, "must be true or false (got " + typeName(*v) + ")");
  return v->get<bool>();
}

std::string JsonObject::string(const std::string& key, std::optional<std::string> fallback) {
  const nlohmann::json* v = raw(key);
  if (!v) {
    if (!fallback) fail(key, "missing (required, a string)");
    return *fallback;
  }
  if (!v->is_string()) fail(key, "must be a string (got " + typeName(*v) + ")");
  return v->get<std::string>();
}

std::string JsonObject::choice(const std::string& key, std::optional<std::string> fallback,
                               const std::vector<std::string>& choices) {
  const std::string text = string(key, std::move(fallback));
  for (const std::string& c : choices) {
    if (c == text) return text;
  }
  std::string list;
  for (const std::string& c : choices) list += (list.empty() ? "" : ", ") + c;
  fail(key, "unknown value '" + text + "' (one of: " + list + ")");
}

Eigen::Vector3d JsonObject::vector3(const std::string& key, std::optional<Eigen::Vector3d> fallback,
                                    double min, double max, std::optional<double> z_fallback) {
  const nlohmann::json* v = raw(key);
  if (!v) {
    if (!fallback) fail(key, "missing (required, [x, y, z])");
    return *fallback;
  }
  const bool two_ok = z_fallback.has_value();
  if (!v->is_array() || v->size() > 3 || v->size() < (two_ok ? 2u : 3u)) {
    fail(key, std::string("must be an array ") + (two_ok ? "[x, y] or [x, y, z]" : "[x, y, z]") + " (got " +
                  (v->is_array() ? std::to_string(v->size()) + " items" : typeName(*v)) + ")");
  }
  Eigen::Vector3d out(0, 0, z_fallback.value_or(0));
  for (std::size_t i = 0; i < v->size(); ++i) {
    const nlohmann::json& item = (*v)[i];
    const std::string item_key = key + "[" + std::to_string(i) + "]";
    if (!item.is_number()) fail(item_key, "must be a number (got " + typeName(item) + ")");
    const double x = item.get<double>();
    if (!std::isfinite(x) || x < min || x > max) {
      fail(item_key, "must be in [" + show(min) + ", " + show(max) + "] (got " + show(x) + ")");
    }
    out[static_cast<Eigen::Index>(i)] = x;
  }
  return out;
}

std::optional<JsonObject> JsonObject::object(const std::string& key, bool required) {
  const nlohmann::json* v = raw(key);
  if (!v) {
    if (required) fail(key, "missing (required, an object)");
    return std::nullopt;
  }
  return JsonObject(*v, keyPath(key), *source_);
}

std::vector<JsonObject> JsonObject::objects(const std::string& key, bool required) {
  const nlohmann::json* v = raw(key);
  std::vector<JsonObject> out;
  if (!v) {
    if (required) fail(key, "missing (required, an array of objects)");
    return out;
  }
  if (!v->is_array()) fail(key, "must be an array (got " + typeName(*v) + ")");
  for (std::size_t i = 0; i < v->size(); ++i) {
    out.emplace_back((*v)[i], keyPath(key) + "[" + std::to_string(i) + "]", *source_);
  }
  return out;
}

void JsonObject::finish() const {
  for (auto it = value_->begin(); it != value_->end(); ++it) {
    if (!read_.count(it.key())) fail(it.key(), "unknown key");
  }
}

}  // namespace scenes::detail

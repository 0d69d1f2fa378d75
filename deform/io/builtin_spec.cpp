// "builtin:NAME?key=value&..." specs: parsed and checked where they enter (DESIGN.md section 9).
#include <deform/builtin_meshes.hpp>
#include <deform/error.hpp>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <string_view>

namespace deform {
namespace {

constexpr std::string_view kPrefix = "builtin:";
constexpr std::size_t kMinVertices = 100;
constexpr std::size_t kMaxVertices = 50'000'000;
constexpr double kMaxSize_m = 1000.0;

/// 'text' in quotes (built by appending: GCC 12 warns falsely on "'" + std::string).
std::string quoted(std::string_view text) {
  std::string q = "'";
  q += text;
  q += "'";
  return q;
}

/// The key=value pairs of a spec, each checked against the keys its shape accepts.
class SpecQuery {
 public:
  SpecQuery(const std::string& spec, std::string_view query, std::initializer_list<std::string_view> known)
      : spec_(spec) {
    while (!query.empty()) {
      const std::size_t amp = query.find('&');
      const std::string_view pair = query.substr(0, amp);
      query = amp == std::string_view::npos ? std::string_view{} : query.substr(amp + 1);
      if (pair.empty()) continue;
      const std::size_t eq = pair.find('=');
      if (eq == std::string_view::npos) fail(quoted(pair) + " is not key=value");
      const std::string key(pair.substr(0, eq));
      bool is_known = false;
      std::string known_list;
      for (std::string_view k : known) {
        is_known = is_known || k == key;
        if (!known_list.empty()) known_list += ", ";
        known_list += k;
      }
      if (!is_known) fail("unknown key " + quoted(key) + " (known: " + known_list + ")");
      if (!values_.emplace(key, std::string(pair.substr(eq + 1))).second) fail(quoted(key) + " given twice");
    }
  }

  std::size_t vertices(std::size_t fallback) const {
    const auto it = values_.find("vertices");
    if (it == values_.end()) return fallback;
    const std::string& text = it->second;
    const bool digits =
        !text.empty() && text.size() <= 12 && text.find_first_not_of("0123456789") == std::string::npos;
    if (!digits) fail("'vertices' must be a positive integer (got " + quoted(text) + ")");
    const auto n = static_cast<std::size_t>(std::stoull(text));
    if (n < kMinVertices || n > kMaxVertices)
      fail("'vertices' must be between " + std::to_string(kMinVertices) + " and " +
           std::to_string(kMaxVertices) + " (got " + text + ")");
    return n;
  }

  double size_m(const std::string& key, double fallback) const {
    const auto it = values_.find(key);
    if (it == values_.end()) return fallback;
    const std::string& text = it->second;
    char* end = nullptr;
    errno = 0;
    const double value = text.empty() ? NAN : std::strtod(text.c_str(), &end);
    const bool parsed = !text.empty() && end == text.c_str() + text.size() && errno == 0;
    if (!parsed || !std::isfinite(value) || value <= 0 || value > kMaxSize_m)
      fail(quoted(key) + " must be a positive size in metres up to " +
           std::to_string(static_cast<int>(kMaxSize_m)) + " (got " + quoted(text) + ")");
    return value;
  }

  [[noreturn]] void fail(const std::string& message) const { throw InputError(spec_ + ": " + message); }

 private:
  std::string spec_;
  std::map<std::string, std::string> values_;
};

}  // namespace

bool isBuiltinSpec(const std::string& spec) {
  return spec.rfind(kPrefix, 0) == 0;
}

VehicleModel makeBuiltin(const std::string& spec) {
  if (!isBuiltinSpec(spec)) throw InputError(spec + ": not a built-in mesh (expected builtin:NAME)");
  const std::string_view rest = std::string_view(spec).substr(kPrefix.size());
  const std::size_t question = rest.find('?');
  const std::string name(rest.substr(0, question));
  const std::string_view query =
      question == std::string_view::npos ? std::string_view{} : rest.substr(question + 1);

  VehicleModel model;
  if (name == "sedan") {
    const SpecQuery q(spec, query, {"vertices"});
    model = makeSedan(q.vertices(20000));
  } else if (name == "can") {
    const SpecQuery q(spec, query, {"vertices"});
    model.body = makeCan(q.vertices(4000));
  } else if (name == "box") {
    const SpecQuery q(spec, query, {"x", "y", "z", "vertices"});
    const Eigen::Vector3d size(q.size_m("x", 1.0), q.size_m("y", 1.0), q.size_m("z", 1.0));
    model.body = makeBox(size, q.vertices(600));
  } else {
    throw InputError(spec + ": unknown built-in '" + name + "' (known: sedan, can, box)");
  }
  model.source = spec;
  checkMesh(model.body, spec);
  return model;
}

}  // namespace deform

#include "anisodyn/tool/json_config.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "anisodyn/core/error.hpp"

namespace anisodyn::tool {

using nlohmann::json;

// ---- loading --------------------------------------------------------------------------------------

json parse_json_text(std::string_view text, const std::string& source_name) {
  try {
    return json::parse(text.begin(), text.end());
  } catch (const json::parse_error& e) {
    // e.byte is the 1-based index of the last character the lexer read.
    const std::size_t end = std::min<std::size_t>(e.byte == 0 ? 0 : e.byte - 1, text.size());
    std::size_t line = 1, line_start = 0;
    for (std::size_t i = 0; i < end; ++i) {
      if (text[i] == '\n') { ++line; line_start = i + 1; }
    }
    const std::size_t column = end - line_start + 1;
    // Keep the parser's explanation, drop its "[json.exception…] parse error at line…:" prefix.
    std::string detail = e.what();
    const auto col = detail.find("column ");
    const auto colon = detail.find(": ", col == std::string::npos ? 0 : col);
    if (colon != std::string::npos) detail = detail.substr(colon + 2);
    throw InputError(source_name, "",
                     "invalid JSON at line " + std::to_string(line) + ", column " + std::to_string(column) +
                         ": " + detail);
  }
}

json load_json_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, "", "cannot open file: it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", std::string("cannot open file: ") + std::strerror(errno));
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw InputError(path, "", "cannot read file");
  return parse_json_text(buffer.str(), path);
}

// ---- --set overrides -------------------------------------------------------------------------------

namespace {

struct PathToken {
  std::string name;       // object key (also the text of a numeric dotted segment)
  bool bracket = false;   // written as [i]: must index an array
  bool numeric = false;   // all digits: an array index when the target is an array
  std::size_t index = 0;
};

bool all_digits(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

[[noreturn]] void malformed(const std::string& assignment) {
  throw InputError("--set", "", "expected key.path=value, got '" + assignment + "'");
}

std::vector<PathToken> parse_key_path(const std::string& key, const std::string& assignment) {
  std::vector<PathToken> tokens;
  std::size_t i = 0;
  const std::size_t n = key.size();
  while (true) {
    // A segment: name, then any number of [index].
    std::string name;
    while (i < n && key[i] != '.' && key[i] != '[' && key[i] != ']') name += key[i++];
    if (name.empty() || (i < n && key[i] == ']')) malformed(assignment);  // "", "a..b", "[2]" without a key
    PathToken t;
    t.name = name;
    t.numeric = all_digits(name) && name.size() <= 18;
    if (t.numeric) t.index = std::stoull(name);
    tokens.push_back(t);
    while (i < n && key[i] == '[') {
      const std::size_t close = key.find(']', i);
      if (close == std::string::npos) malformed(assignment);
      const std::string digits = key.substr(i + 1, close - i - 1);
      if (!all_digits(digits) || digits.size() > 18) malformed(assignment);
      PathToken t;
      t.name = digits;
      t.bracket = t.numeric = true;
      t.index = std::stoull(digits);
      tokens.push_back(t);
      i = close + 1;
    }
    if (i == n) break;
    if (key[i] != '.') malformed(assignment);
    ++i;
    if (i == n) malformed(assignment);
  }
  return tokens;
}

std::string render_path(const std::vector<PathToken>& tokens, std::size_t count) {
  std::string out;
  for (std::size_t k = 0; k < count; ++k) {
    if (tokens[k].bracket) out += "[" + tokens[k].name + "]";
    else out += (out.empty() ? "" : ".") + tokens[k].name;
  }
  return out;
}

const char* type_phrase(const json& j) {
  switch (j.type()) {
    case json::value_t::null: return "null";
    case json::value_t::object: return "an object";
    case json::value_t::array: return "an array";
    case json::value_t::string: return "a string";
    case json::value_t::boolean: return "a boolean";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float: return "a number";
    default: return "a value";
  }
}

}  // namespace

void apply_override(json& config, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) malformed(assignment);
  const std::string key = assignment.substr(0, eq);
  const std::string text = assignment.substr(eq + 1);
  const std::vector<PathToken> tokens = parse_key_path(key, assignment);

  json value = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (value.is_discarded()) value = text;

  json* node = &config;
  for (std::size_t k = 0; k < tokens.size(); ++k) {
    const PathToken& t = tokens[k];
    const std::string here = render_path(tokens, k);
    if (node->is_null() && !t.bracket) *node = json::object();
    if (node->is_array() && t.numeric) {
      if (t.index >= node->size()) {
        throw InputError("--set", render_path(tokens, k + 1),
                         "index " + t.name + " is out of range (the array at " + (here.empty() ? "top level" : here) +
                             " has " + std::to_string(node->size()) + " elements)");
      }
      node = &(*node)[t.index];
    } else if (node->is_object() && !t.bracket) {
      node = &(*node)[t.name];
    } else {
      const std::string what = t.bracket ? "an array" : "an object";
      throw InputError("--set", render_path(tokens, k + 1),
                       "cannot set '" + key + "': " + (here.empty() ? std::string("the configuration") : "'" + here + "'") +
                           " is " + type_phrase(*node) + ", not " + what);
    }
  }
  *node = std::move(value);
}

void apply_overrides(json& config, const std::vector<std::string>& assignments) {
  for (const auto& a : assignments) apply_override(config, a);
}

std::string describe_json_value(const json& value) {
  std::string s = value.dump(-1, ' ', false, json::error_handler_t::replace);
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

// ---- ConfigNode ---------------------------------------------------------------------------------

struct ConfigNode::Usage {
  std::set<std::string> read;    // present keys that were consumed (or marked)
  std::set<std::string> asked;   // every key the program asked for
  std::map<std::string, std::shared_ptr<Usage>> children;  // child object nodes by "key" / "key[i]"
  const json* node = nullptr;
  std::string path;
};

namespace {

std::string join_path(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t sub = prev[j - 1] + (std::tolower(a[i - 1]) == std::tolower(b[j - 1]) ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, sub});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

}  // namespace

ConfigNode::ConfigNode(const json& j, std::string file, std::string path)
    : doc_(std::make_shared<const json>(j)), j_(doc_.get()), file_(std::move(file)), path_(std::move(path)),
      usage_(std::make_shared<Usage>()) {
  usage_->node = j_;
  usage_->path = path_;
  if (!j_->is_object())
    throw InputError(file_, path_, "expected an object, got " + describe_json_value(*j_));
}

ConfigNode::ConfigNode(std::shared_ptr<const json> doc, const json* j, std::string file, std::string path,
                       std::shared_ptr<Usage> usage)
    : doc_(std::move(doc)), j_(j), file_(std::move(file)), path_(std::move(path)), usage_(std::move(usage)) {}

std::string ConfigNode::child_path(const std::string& key) const { return join_path(path_, key); }

bool ConfigNode::has(const std::string& key) const {
  usage_->asked.insert(key);
  const auto it = j_->find(key);
  if (it == j_->end()) return false;
  if (it->is_null()) { usage_->read.insert(key); return false; }
  return true;
}

void ConfigNode::reject_unless(bool applies, const std::string& key, const std::string& reason) {
  if (!applies && has(key)) fail(key, "no '" + key + "': it has no effect " + reason);
  mark_used(key);
}

void ConfigNode::fail(const std::string& key, const std::string& expected) const {
  const std::string where = key.empty() ? path_ : child_path(key);
  std::string problem = expected;
  if (key.empty()) {
    problem += ", got " + describe_json_value(*j_);
  } else if (const auto it = j_->find(key); it != j_->end()) {
    problem += ", got " + describe_json_value(*it);
  }
  throw InputError(file_, where, problem);
}

const json* ConfigNode::lookup(const std::string& key, const char* what, bool required) {
  usage_->asked.insert(key);
  const auto it = j_->find(key);
  if (it == j_->end()) {
    if (required) throw InputError(file_, child_path(key), std::string("required value is missing (expected ") + what + ")");
    return nullptr;
  }
  usage_->read.insert(key);
  if (it->is_null()) {
    if (required) fail(key, std::string("expected ") + what);
    return nullptr;
  }
  return &*it;
}

void ConfigNode::mark_used(const std::string& key) {
  usage_->asked.insert(key);
  usage_->read.insert(key);
}

const json& ConfigNode::value(const std::string& key) { return *lookup(key, "a value", true); }

// -- numbers

namespace {
constexpr const char* kNumber = "a number";
constexpr const char* kPositive = "a positive number";
constexpr const char* kNonNegative = "a non-negative number";
constexpr const char* kInteger = "an integer";
constexpr const char* kPositiveInteger = "a positive integer";
constexpr const char* kNonNegativeInteger = "a non-negative integer";
std::string expected(const char* what) { return std::string("expected ") + what; }

bool as_integer(const json& v, std::int64_t& out) {
  if (v.is_number_integer() && !v.is_number_unsigned()) { out = v.get<std::int64_t>(); return true; }
  if (v.is_number_unsigned()) {
    const auto u = v.get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(INT64_MAX)) return false;
    out = static_cast<std::int64_t>(u);
    return true;
  }
  if (v.is_number_float()) {
    const double d = v.get<double>();
    if (!std::isfinite(d) || d != std::trunc(d) || std::abs(d) > 9.0e18) return false;
    out = static_cast<std::int64_t>(d);
    return true;
  }
  return false;
}
}  // namespace

#define ANISODYN_NUMBER_GETTER(NAME, EXPECTED, CONDITION)                            \
  double ConfigNode::NAME(const std::string& key) {                                  \
    const json* v = lookup(key, EXPECTED, true);                                 \
    if (!v->is_number()) fail(key, expected(EXPECTED));                                        \
    const double x = v->get<double>();                                               \
    if (!(CONDITION)) fail(key, expected(EXPECTED));                                           \
    return x;                                                                        \
  }                                                                                  \
  double ConfigNode::NAME(const std::string& key, double fallback) {                 \
    const json* v = lookup(key, EXPECTED, false);                                \
    if (!v) return fallback;                                                         \
    if (!v->is_number()) fail(key, expected(EXPECTED));                                        \
    const double x = v->get<double>();                                               \
    if (!(CONDITION)) fail(key, expected(EXPECTED));                                           \
    return x;                                                                        \
  }

ANISODYN_NUMBER_GETTER(number, kNumber, std::isfinite(x))
ANISODYN_NUMBER_GETTER(positive, kPositive, std::isfinite(x) && x > 0)
ANISODYN_NUMBER_GETTER(non_negative, kNonNegative, std::isfinite(x) && x >= 0)
#undef ANISODYN_NUMBER_GETTER

#define ANISODYN_INTEGER_GETTER(NAME, EXPECTED, CONDITION)                                 \
  std::int64_t ConfigNode::NAME(const std::string& key) {                                  \
    const json* v = lookup(key, EXPECTED, true);                                       \
    std::int64_t x = 0;                                                                    \
    if (!as_integer(*v, x) || !(CONDITION)) fail(key, expected(EXPECTED));                           \
    return x;                                                                              \
  }                                                                                        \
  std::int64_t ConfigNode::NAME(const std::string& key, std::int64_t fallback) {           \
    const json* v = lookup(key, EXPECTED, false);                                      \
    if (!v) return fallback;                                                               \
    std::int64_t x = 0;                                                                    \
    if (!as_integer(*v, x) || !(CONDITION)) fail(key, expected(EXPECTED));                           \
    return x;                                                                              \
  }

ANISODYN_INTEGER_GETTER(integer, kInteger, true)
ANISODYN_INTEGER_GETTER(positive_integer, kPositiveInteger, x >= 1)
ANISODYN_INTEGER_GETTER(non_negative_integer, kNonNegativeInteger, x >= 0)
#undef ANISODYN_INTEGER_GETTER

// -- booleans and strings

bool ConfigNode::boolean(const std::string& key) {
  const json* v = lookup(key, "true or false", true);
  if (!v->is_boolean()) fail(key, "expected true or false");
  return v->get<bool>();
}

bool ConfigNode::boolean(const std::string& key, bool fallback) {
  const json* v = lookup(key, "true or false", false);
  if (!v) return fallback;
  if (!v->is_boolean()) fail(key, "expected true or false");
  return v->get<bool>();
}

std::string ConfigNode::string(const std::string& key) {
  const json* v = lookup(key, "a string", true);
  if (!v->is_string()) fail(key, "expected a string");
  return v->get<std::string>();
}

std::string ConfigNode::string(const std::string& key, const std::string& fallback) {
  const json* v = lookup(key, "a string", false);
  if (!v) return fallback;
  if (!v->is_string()) fail(key, "expected a string");
  return v->get<std::string>();
}

namespace {
std::string one_of(const std::vector<std::string>& allowed) {
  std::string s = "one of ";
  for (std::size_t i = 0; i < allowed.size(); ++i) s += (i ? ", " : "") + json(allowed[i]).dump();
  return s;
}
}  // namespace

std::string ConfigNode::choice(const std::string& key, const std::vector<std::string>& allowed) {
  const std::string what = one_of(allowed);
  const json* v = lookup(key, what.c_str(), true);
  if (!v->is_string() || std::find(allowed.begin(), allowed.end(), v->get<std::string>()) == allowed.end())
    fail(key, "expected " + what);
  return v->get<std::string>();
}

std::string ConfigNode::choice(const std::string& key, const std::vector<std::string>& allowed,
                               const std::string& fallback) {
  const std::string what = one_of(allowed);
  const json* v = lookup(key, what.c_str(), false);
  if (!v) return fallback;
  if (!v->is_string() || std::find(allowed.begin(), allowed.end(), v->get<std::string>()) == allowed.end())
    fail(key, "expected " + what);
  return v->get<std::string>();
}

// -- arrays

namespace {
bool read_vec3(const json& v, Vec3& out, bool positive) {
  if (!v.is_array() || v.size() != 3) return false;
  for (int k = 0; k < 3; ++k) {
    if (!v[k].is_number()) return false;
    out[k] = v[k].get<double>();
    if (!std::isfinite(out[k]) || (positive && !(out[k] > 0))) return false;
  }
  return true;
}
}  // namespace

Vec3 ConfigNode::vec3(const std::string& key) {
  const json* v = lookup(key, "an array of 3 numbers", true);
  Vec3 out;
  if (!read_vec3(*v, out, false)) fail(key, "expected an array of 3 numbers");
  return out;
}

Vec3 ConfigNode::vec3(const std::string& key, const Vec3& fallback) {
  const json* v = lookup(key, "an array of 3 numbers", false);
  if (!v) return fallback;
  Vec3 out;
  if (!read_vec3(*v, out, false)) fail(key, "expected an array of 3 numbers");
  return out;
}

Vec3 ConfigNode::positive_vec3(const std::string& key) {
  const json* v = lookup(key, "an array of 3 positive numbers", true);
  Vec3 out;
  if (!read_vec3(*v, out, true)) fail(key, "expected an array of 3 positive numbers");
  return out;
}

Vec3 ConfigNode::positive_vec3(const std::string& key, const Vec3& fallback) {
  const json* v = lookup(key, "an array of 3 positive numbers", false);
  if (!v) return fallback;
  Vec3 out;
  if (!read_vec3(*v, out, true)) fail(key, "expected an array of 3 positive numbers");
  return out;
}

std::vector<double> ConfigNode::numbers(const std::string& key) {
  const json* v = lookup(key, "an array of numbers", true);
  if (!v->is_array()) fail(key, "expected an array of numbers");
  std::vector<double> out;
  for (const auto& e : *v) {
    if (!e.is_number()) fail(key, "expected an array of numbers");
    out.push_back(e.get<double>());
  }
  return out;
}

std::vector<std::string> ConfigNode::strings(const std::string& key) {
  const json* v = lookup(key, "an array of strings", true);
  if (!v->is_array()) fail(key, "expected an array of strings");
  std::vector<std::string> out;
  for (const auto& e : *v) {
    if (!e.is_string()) fail(key, "expected an array of strings");
    out.push_back(e.get<std::string>());
  }
  return out;
}

// -- objects

ConfigNode ConfigNode::child(const std::string& /*key*/, const std::string& usage_key, const std::string& path,
                             const json& j) {
  auto& slot = usage_->children[usage_key];
  if (!slot) {
    slot = std::make_shared<Usage>();
    slot->node = &j;
    slot->path = path;
  }
  return ConfigNode(doc_, &j, file_, path, slot);
}

ConfigNode ConfigNode::object(const std::string& key) {
  const json* v = lookup(key, "an object", true);
  if (!v->is_object()) fail(key, "expected an object");
  return child(key, key, child_path(key), *v);
}

std::optional<ConfigNode> ConfigNode::optional_object(const std::string& key) {
  const json* v = lookup(key, "an object", false);
  if (!v) return std::nullopt;
  if (!v->is_object()) fail(key, "expected an object");
  return child(key, key, child_path(key), *v);
}

std::vector<ConfigNode> ConfigNode::objects(const std::string& key) {
  const json* v = lookup(key, "an array of objects", true);
  if (!v->is_array()) fail(key, "expected an array of objects");
  std::vector<ConfigNode> out;
  for (std::size_t i = 0; i < v->size(); ++i) {
    const std::string element = key + "[" + std::to_string(i) + "]";
    if (!(*v)[i].is_object())
      throw InputError(file_, join_path(path_, element), "expected an object, got " + describe_json_value((*v)[i]));
    out.push_back(child(key, element, join_path(path_, element), (*v)[i]));
  }
  return out;
}

// -- unknown keys

void ConfigNode::finish() const {
  // Walk this node and every child created from it, in a deterministic order.
  std::vector<const Usage*> stack{usage_.get()};
  while (!stack.empty()) {
    const Usage* u = stack.back();
    stack.pop_back();
    for (const auto& [key, value] : u->node->items()) {
      (void)value;
      if (!key.empty() && key[0] == '_') continue;
      if (u->read.count(key)) continue;
      std::string problem = "unknown key '" + key + "'";
      std::string best;
      std::size_t best_d = std::string::npos;
      for (const auto& candidate : u->asked) {
        if (u->node->contains(candidate)) continue;
        const std::size_t d = edit_distance(key, candidate);
        if (d < best_d) { best_d = d; best = candidate; }
      }
      if (!best.empty() && best_d <= std::max<std::size_t>(2, key.size() / 3)) {
        problem += " (did you mean '" + best + "'?)";
      } else if (!u->asked.empty() && u->asked.size() <= 16) {
        problem += " (known keys here:";
        bool first = true;
        for (const auto& a : u->asked) { problem += (first ? " " : ", ") + a; first = false; }
        problem += ")";
      }
      throw InputError(file_, join_path(u->path, key), problem);
    }
    for (auto it = u->children.rbegin(); it != u->children.rend(); ++it) stack.push_back(it->second.get());
  }
}

}  // namespace anisodyn::tool

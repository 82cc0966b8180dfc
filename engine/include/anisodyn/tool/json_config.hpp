#pragma once
// JSON parameter files: loading with precise syntax errors, `--set key.path=value` overrides, and
// ConfigNode, a typed reader that names the file, the JSON path and what was expected in every
// error and detects unknown (misspelt) keys.
//
// Typical use in a tool:
//   nlohmann::json j = tool::load_json_file(config_path);
//   for (const auto& s : overrides) tool::apply_override(j, s);
//   tool::ConfigNode cfg(j, config_path);
//   const double phi = cfg.positive("packing_fraction");
//   for (auto& sp : cfg.objects("species")) { ... sp.vec3("edges") ...; }
//   cfg.finish();   // unknown keys anywhere in the tree → InputError
//
// Paths are rendered the way --set takes them: `species[1].shape.edges`.
// Conventions: an optional key that is present with the value null counts as absent (so
// `--set key=null` restores a default); keys starting with '_' are comments and never reported
// as unknown.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/core/types.hpp"

namespace anisodyn::tool {

/// Reads and parses a JSON file. Missing/unreadable → InputError(path, "", "cannot open file: …");
/// syntax error → InputError(path, "", "invalid JSON at line L, column C: <parser message>").
nlohmann::json load_json_file(const std::string& path);

/// Parses JSON text; errors are reported as for load_json_file with `source_name` as the file.
nlohmann::json parse_json_text(std::string_view text, const std::string& source_name);

/// Applies one `--set key.path=value` assignment. The path is dotted, array elements are `key[2]`
/// or `key.2`; missing object keys (and objects) are created; array indices must exist. The value
/// is parsed as JSON when it parses (numbers, true/false/null, arrays, objects, "quoted"), otherwise
/// it is taken as a plain string. Malformed assignment → InputError("--set", "", "expected
/// key.path=value, got '…'"); a path through a non-object → InputError("--set", <path>, …).
void apply_override(nlohmann::json& config, const std::string& assignment);
void apply_overrides(nlohmann::json& config, const std::vector<std::string>& assignments);

/// A JSON value for an error message: compact, truncated to ~60 characters.
std::string describe_json_value(const nlohmann::json& value);

class ConfigNode {
 public:
  /// `j` must be an object (else InputError). The document is copied once at the root and shared
  /// by all child nodes, so temporaries are fine: ConfigNode(load_json_file(p), p).
  ConfigNode(const nlohmann::json& j, std::string file, std::string path = "");

  /// Present and not null. Does not count as reading the key (see finish()).
  bool has(const std::string& key) const;

  double number(const std::string& key);
  double number(const std::string& key, double fallback);
  double positive(const std::string& key);                     // > 0
  double positive(const std::string& key, double fallback);
  double non_negative(const std::string& key);                 // ≥ 0
  double non_negative(const std::string& key, double fallback);
  /// Integers also accept integral floating-point values (1e6).
  std::int64_t integer(const std::string& key);
  std::int64_t integer(const std::string& key, std::int64_t fallback);
  std::int64_t positive_integer(const std::string& key);       // ≥ 1
  std::int64_t positive_integer(const std::string& key, std::int64_t fallback);
  std::int64_t non_negative_integer(const std::string& key);   // ≥ 0
  std::int64_t non_negative_integer(const std::string& key, std::int64_t fallback);
  bool boolean(const std::string& key);
  bool boolean(const std::string& key, bool fallback);
  std::string string(const std::string& key);
  std::string string(const std::string& key, const std::string& fallback);
  /// One of `allowed`; the error lists them.
  std::string choice(const std::string& key, const std::vector<std::string>& allowed);
  std::string choice(const std::string& key, const std::vector<std::string>& allowed, const std::string& fallback);
  Vec3 vec3(const std::string& key);                           // array of 3 numbers
  Vec3 vec3(const std::string& key, const Vec3& fallback);
  Vec3 positive_vec3(const std::string& key);                  // array of 3 positive numbers
  Vec3 positive_vec3(const std::string& key, const Vec3& fallback);
  std::vector<double> numbers(const std::string& key);         // array of numbers (any length)
  std::vector<std::string> strings(const std::string& key);    // array of strings (any length)

  ConfigNode object(const std::string& key);
  std::optional<ConfigNode> optional_object(const std::string& key);
  /// Array of objects; the children's paths are key[i].
  std::vector<ConfigNode> objects(const std::string& key);

  /// Any JSON value (required), marked as read — for blocks passed through verbatim.
  const nlohmann::json& value(const std::string& key);
  /// Marks a key as known without reading it (it is then never reported by finish()).
  void mark_used(const std::string& key);

  const nlohmann::json& raw() const { return *j_; }
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }
  /// Path of a child key: "species[0].mass".
  std::string child_path(const std::string& key) const;

  /// For a key that acts only in some modes: unless `applies`, its presence is an InputError saying
  /// that it has no effect `reason` (e.g. "unless balance.mode is \"per_cycle\""), since a key that
  /// is silently ignored hides a mistake. Marks the key as known either way.
  void reject_unless(bool applies, const std::string& key, const std::string& reason);

  /// InputError(file, path.key, expected [+ ", got <value>" when the key is present]).
  /// An empty key names this node itself.
  [[noreturn]] void fail(const std::string& key, const std::string& expected) const;

  /// Throws InputError for the first key, in this node or any node created from it, that is
  /// present but was never read: "unknown key 'tempreature' (did you mean 'temperature'?)".
  void finish() const;

 private:
  struct Usage;
  ConfigNode(std::shared_ptr<const nlohmann::json> doc, const nlohmann::json* j, std::string file,
             std::string path, std::shared_ptr<Usage> usage);
  const nlohmann::json* lookup(const std::string& key, const char* what, bool required);
  ConfigNode child(const std::string& key, const std::string& usage_key, const std::string& path,
                   const nlohmann::json& j);

  std::shared_ptr<const nlohmann::json> doc_;
  const nlohmann::json* j_ = nullptr;
  std::string file_, path_;
  std::shared_ptr<Usage> usage_;
};

/// Dispatches on node[key] over a registry of {const char* type; Result (*parse)(ConfigNode&)}
/// entries (one line per registered type): unknown types get the list of known ones.
template <class Registry>
auto parse_registered(ConfigNode& node, const std::string& key, const Registry& registry) {
  std::vector<std::string> names;
  for (const auto& r : registry) names.emplace_back(r.type);
  const std::string type = node.choice(key, names);
  for (const auto& r : registry)
    if (type == r.type) return r.parse(node);
  node.fail(key, "expected a known type");
}

}  // namespace anisodyn::tool

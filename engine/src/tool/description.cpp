#include "anisodyn/tool/description.hpp"

#include <utility>

namespace anisodyn::tool {

Parameter required(std::string name, std::string type, std::string meaning) {
  return {std::move(name), std::move(type), true, nullptr, std::move(meaning)};
}

Parameter optional(std::string name, std::string type, nlohmann::json default_value, std::string meaning) {
  return {std::move(name), std::move(type), false, std::move(default_value), std::move(meaning)};
}

Parameter seed_parameter() {
  return optional("seed", "integer", 1, "random seed; --seed overrides it, --replica K draws stream K");
}

nlohmann::json negligible_cost(const std::string& why) { return {{"kind", "negligible"}, {"why", why}}; }

Description engine_description(const std::string& output_meaning) {
  Description d;
  d.role = Role::Engine;
  d.replica = true;
  d.inputs = {"state", 1, 1, "the starting state (its last frame)"};
  d.output = {"trajectory", "H5MD", output_meaning, nullptr};
  return d;
}

const char* role_name(Role role) {
  switch (role) {
    case Role::Builder: return "builder";
    case Role::Engine: return "engine";
    case Role::Analysis: return "analysis";
    case Role::Tensors: return "tensors";
    case Role::Example: return "example";
    case Role::Dispatcher: return "dispatcher";
  }
  return "unknown";
}

}  // namespace anisodyn::tool

#pragma once
// The "field" block, one schema for every engine (docs/run.md):
//   "field": {"direction": [x, y, z],                       default [1, 0, 0]
//             "orientational": {"strength": ε_f*, "axis": "T" | "W" | "L"},   axis default W
//             "dipoles": {"gamma", "species", "accuracy", "minimum_image_only"},
//             "initially": "on" | "off", "check_direction": bool}
// An engine states which parts it supports; a part it does not support is an input error naming it,
// never silently ignored. MC preparation keeps its field on throughout: it takes direction and
// orientational only.
#include <optional>
#include <string>
#include <vector>

#include "anisodyn/interactions/orientational_field.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::run {

struct DipoleConfig {
  double gamma = 0.0;                // Γ = βμ²/σ³
  std::vector<std::string> species;  // the species that carry a dipole along the field
  double accuracy = 1e-5;            // relative Ewald accuracy
  bool minimum_image_only = false;   // truncated minimum-image sum (smoke tests only)
};

struct FieldConfig {
  OrientationalField orientational;  // strength 0: none
  std::optional<DipoleConfig> dipoles;
  bool initially_on = false;         // before the schedule's first switch
  bool check_direction = true;       // turn an on-switched field perpendicular to the director
  bool any() const { return orientational.active() || dipoles.has_value(); }
};

/// What a tool does with its field.
enum class FieldUse {
  Constant,    // on for the whole run (MC preparation): direction and orientational only
  Switchable,  // switched by the schedule (DMC production): every key
};

/// Parses the optional "field" block of `cfg` (absent: no field).
FieldConfig parse_field_config(tool::ConfigNode& cfg, FieldUse use);

}  // namespace anisodyn::run

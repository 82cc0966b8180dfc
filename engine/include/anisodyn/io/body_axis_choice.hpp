#pragma once
// The one reader of body-axis keys in configurations (every tool that takes one uses it).
#include <string>
#include <vector>

#include "anisodyn/geometry/body_axes.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::io {

/// T, W, L, then x, y, z when `letters`, then the specials: what a body-axis key accepts.
inline std::vector<std::string> body_axis_choices(bool letters, const std::vector<std::string>& specials) {
  std::vector<std::string> allowed(kBodyAxisNames.begin(), kBodyAxisNames.end());
  if (letters) allowed.insert(allowed.end(), kBodyAxisLetters.begin(), kBodyAxisLetters.end());
  allowed.insert(allowed.end(), specials.begin(), specials.end());
  return allowed;
}

/// Reads `key` as a body axis and returns 0, 1 or 2: T, W or L, and x, y or z for the same axes
/// when `letters`; or one of `specials` (e.g. "auto", "none"), which give −1. Absent → fallback.
/// Anything else is an InputError listing the choices.
inline int choose_body_axis(tool::ConfigNode& cfg, const std::string& key, const std::string& fallback, bool letters,
                            const std::vector<std::string>& specials = {}) {
  return body_axis_index(cfg.choice(key, body_axis_choices(letters, specials), fallback), letters);
}

/// The same for a key that must be given.
inline int require_body_axis(tool::ConfigNode& cfg, const std::string& key, bool letters) {
  return body_axis_index(cfg.choice(key, body_axis_choices(letters, {})), letters);
}

}  // namespace anisodyn::io

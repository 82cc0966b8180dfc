#pragma once
// Names of the body axes: T, W and L are body x, y and z (geometry/shape.hpp), so the columns of a
// rotation matrix are ê_T, ê_W, ê_L. Where a configuration may also name them by the letters x, y,
// z, those mean the same body axes.
#include <array>
#include <string_view>

namespace anisodyn {

inline constexpr std::array<const char*, 3> kBodyAxisNames{"T", "W", "L"};
inline constexpr std::array<const char*, 3> kBodyAxisLetters{"x", "y", "z"};

/// 0, 1 or 2 for T, W, L (and for x, y, z when `letters`); −1 for any other name.
inline int body_axis_index(std::string_view name, bool letters = true) {
  for (int k = 0; k < 3; ++k)
    if (name == kBodyAxisNames[static_cast<std::size_t>(k)] || (letters && name == kBodyAxisLetters[static_cast<std::size_t>(k)]))
      return k;
  return -1;
}

inline const char* body_axis_name(int k) { return kBodyAxisNames[static_cast<std::size_t>(k)]; }

}  // namespace anisodyn

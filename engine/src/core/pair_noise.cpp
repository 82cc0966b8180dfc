#include "anisodyn/core/pair_noise.hpp"

#include <algorithm>
#include <cmath>

#include "anisodyn/core/keyed_random.hpp"
#include "anisodyn/core/philox4x32.hpp"

namespace anisodyn {

PairNoise::PairNoise(std::uint64_t seed, std::uint64_t purpose) { philox4x32_key(seed, purpose, key_); }

void PairNoise::normals(std::uint64_t step, const std::uint32_t* a, const std::uint32_t* b, std::size_t n, double* out) const {
  const auto step_lo = static_cast<std::uint32_t>(step), step_hi = static_cast<std::uint32_t>(step >> 32);
  for (std::size_t first = 0; first < n; first += kPhiloxLanes) {
    const std::size_t lanes = std::min(kPhiloxLanes, n - first);
    std::uint32_t c0[kPhiloxLanes], c1[kPhiloxLanes], c2[kPhiloxLanes], c3[kPhiloxLanes];
    for (std::size_t l = 0; l < kPhiloxLanes; ++l) {
      const std::size_t m = first + std::min(l, lanes - 1);  // spare lanes repeat the last pair
      c0[l] = step_lo;
      c1[l] = step_hi;
      c2[l] = std::min(a[m], b[m]);
      c3[l] = std::max(a[m], b[m]);
    }
    philox4x32_lanes(c0, c1, c2, c3, key_);
    double p[kPhiloxLanes], x[kPhiloxLanes];
    for (std::size_t l = 0; l < kPhiloxLanes; ++l) {
      // 53 bits: all 32 of word 0, the top 21 of word 1; + ½ keeps p inside (0, 1).
      const std::uint64_t bits = (static_cast<std::uint64_t>(c0[l]) << 21) | (c1[l] >> 11);
      p[l] = (static_cast<double>(bits) + 0.5) * 0x1.0p-53;
      x[l] = KeyedRandom::normal_quantile_central(p[l]);
    }
    // The 5% of draws in the tails take the scalar quantile (a logarithm).
    constexpr double low = KeyedRandom::kQuantileCentral;
    for (std::size_t l = 0; l < lanes; ++l) out[first + l] = (p[l] >= low && p[l] <= 1.0 - low) ? x[l] : KeyedRandom::normal_quantile(p[l]);
  }
}

}  // namespace anisodyn

#include "anisodyn/core/node_noise.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "anisodyn/core/keyed_random.hpp"
#include "anisodyn/core/philox4x32.hpp"

namespace anisodyn {

namespace {

/// ln p for normal p > 0, in a form the compiler vectorises (the library's log is one call per
/// value): p = m 2^e with m in [√½, √2), ln m = 2 artanh f, f = (m − 1)/(m + 1), |f| ≤ 0.172, by
/// its series to f¹⁷ (the next term is below 2×10⁻¹⁶ of ln m).
[[gnu::always_inline]] inline double log_vectorisable(double p) {
  std::uint64_t bits;
  std::memcpy(&bits, &p, sizeof bits);
  double e = static_cast<double>(static_cast<std::int64_t>(bits >> 52) - 1023);
  bits = (bits & 0x000FFFFFFFFFFFFFULL) | 0x3FF0000000000000ULL;
  double m;
  std::memcpy(&m, &bits, sizeof m);
  const bool high = m > M_SQRT2;
  m = high ? 0.5 * m : m;
  e = high ? e + 1.0 : e;
  const double f = (m - 1.0) / (m + 1.0), f2 = f * f;
  double series = 1.0 / 17;
  for (int k = 15; k >= 1; k -= 2) series = series * f2 + 1.0 / k;
  return e * M_LN2 + 2.0 * f * series;
}

}  // namespace

NodeNoise::NodeNoise(std::uint64_t seed, std::uint64_t purpose) { philox4x32_key(seed, purpose, key_); }

[[gnu::noinline]] void NodeNoise::normals(std::uint64_t step, std::uint32_t first, std::size_t count, int per_node, double* out, std::size_t stride) const {
  const auto step_lo = static_cast<std::uint32_t>(step), step_hi = static_cast<std::uint32_t>(step >> 32);
  const int blocks = (per_node + 3) / 4;
  for (std::size_t start = 0; start < count; start += kPhiloxLanes) {
    const std::size_t lanes = std::min(kPhiloxLanes, count - start);
    for (int b = 0; b < blocks; ++b) {
      std::uint32_t w[4][kPhiloxLanes];
      for (std::size_t l = 0; l < kPhiloxLanes; ++l) {
        w[0][l] = step_lo;
        w[1][l] = step_hi;
        w[2][l] = first + static_cast<std::uint32_t>(start + std::min(l, lanes - 1));  // spare lanes repeat the last node
        w[3][l] = static_cast<std::uint32_t>(b);
      }
      philox4x32_lanes(w[0], w[1], w[2], w[3], key_);
      for (int j = 0; j < 4 && 4 * b + j < per_node; ++j) {
        double x[kPhiloxLanes];
        constexpr double low = KeyedRandom::kQuantileCentral;
        // Both quantiles for every lane, then the one that applies: one vectorised pass, where a
        // branch to the library's log for the 5% of draws in the tails took a third of the time.
        for (std::size_t l = 0; l < kPhiloxLanes; ++l) {
          const double p = (static_cast<double>(w[j][l]) + 0.5) * 0x1.0p-32;
          const double tail = KeyedRandom::normal_quantile_tail(std::sqrt(-2.0 * log_vectorisable(p < 0.5 ? p : 1.0 - p)));
          x[l] = p >= low && p <= 1.0 - low ? KeyedRandom::normal_quantile_central(p) : p < 0.5 ? tail : -tail;
        }
        double* row = out + static_cast<std::size_t>(4 * b + j) * stride + start;
        std::copy_n(x, lanes, row);
      }
    }
  }
}

// normals() is not inlined here: specialised to one node, the compiler would compute that lane
// alone in scalar code, with its multiply-adds contracted differently (other last bits).
double NodeNoise::operator()(std::uint64_t step, std::uint32_t node, int k) const {
  double out[16];
  normals(step, node, 1, k + 1, out, 1);
  return out[k];
}

}  // namespace anisodyn

#pragma once
// Keyed random numbers: stateless Philox4x64-10 draws whose value depends only on the key
// (seed, purpose tag) and the counter (step, a, b), plus the draw's index k.
//
// Why, next to the sequential Rng: engines with pair noise (DPD), per-particle noise (BD, LB
// beads) or per-node noise (LB) must give the same numbers whatever the thread count and whatever
// order pairs are visited in (spec 00 §7). A draw addressed by (step, particle) or
// (step, min id, max id) has no order at all: any thread can make it at any time, and both sides
// of a pair get the same θ_ij = θ_ji. Different noises of one run take different purpose tags, so
// they are independent (the DPD pair noise and the friction-shell noise of spec 30 §4.3, say).
//
// Normals come from Box–Muller on pairs of 53-bit uniforms, both the cosine and the sine branch:
// one Philox block of four words gives draws 4m … 4m + 3.
#include <Random123/philox.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace anisodyn {

class KeyedRandom {
 public:
  KeyedRandom(std::uint64_t seed, std::uint64_t purpose) : key_{{seed, purpose}} {}

  /// The four words of block m of counter (step, a, b).
  std::array<std::uint64_t, 4> block(std::uint64_t step, std::uint64_t a, std::uint64_t b, std::uint64_t m) const {
    // A Philox counter is four 64-bit words: step, a, b and the block index each take one.
    r123::Philox4x64 gen;
    const r123::Philox4x64::ctr_type ctr = {{step, a, b, m}};
    const auto out = gen(ctr, key_);
    return {out[0], out[1], out[2], out[3]};
  }

  /// Uniform in [0, 1): word k of counter (step, a, b).
  double uniform(std::uint64_t step, std::uint64_t a, std::uint64_t b, std::uint64_t k) const {
    return to_unit(block(step, a, b, k / 4)[k % 4]);
  }

  /// Standard normal draw k of counter (step, a, b): the one Box–Muller branch it needs (the same
  /// value as normals() gives; a DPD pair uses one draw, and the other three branches would double
  /// the cost of its noise).
  double normal(std::uint64_t step, std::uint64_t a, std::uint64_t b, std::uint64_t k) const {
    const auto w = block(step, a, b, k / 4);
    const std::size_t p = (k % 4) / 2;
    const double r = std::sqrt(-2.0 * std::log((static_cast<double>(w[2 * p] >> 11) + 1.0) * 0x1.0p-53));
    const double phi = 2.0 * M_PI * to_unit(w[2 * p + 1]);
    return k % 2 == 0 ? r * std::cos(phi) : r * std::sin(phi);
  }

  /// Normal draws 0 … n−1 of counter (step, a, b) into out (the same values as normal(…, k)).
  void normals(std::uint64_t step, std::uint64_t a, std::uint64_t b, double* out, std::size_t n) const {
    std::array<double, 4> z;
    for (std::size_t m = 0; 4 * m < n; ++m) {
      normal_block(step, a, b, m, z);
      std::copy_n(z.begin(), std::min<std::size_t>(4, n - 4 * m), out + 4 * m);
    }
  }

  /// Acklam's central region: kQuantileCentral ≤ p ≤ 1 − kQuantileCentral.
  static constexpr double kQuantileCentral = 0.02425;
  /// Φ⁻¹(p) in the central region: a rational function of p − ½ (no branch, so it vectorises).
  static double normal_quantile_central(double p) {
    static constexpr double a[6] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                                    1.383577518672690e+02, -3.066479806614716e+01, 2.506628277459239e+00};
    static constexpr double b[5] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                                    6.680131188771972e+01, -1.328068155288572e+01};
    const double q = p - 0.5, r = q * q;
    return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
           (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
  }

  /// Φ⁻¹(p) for 0 < p < 1, by Acklam's rational approximation (relative error below 1.2e-9): a
  /// rational function of p − ½ for 0.02425 ≤ p ≤ 0.97575, which 95% of the draws take, and of
  /// √(−2 ln p) in the tails.
  static double normal_quantile(double p) {
    constexpr double low = kQuantileCentral;
    if (p >= low && p <= 1.0 - low) return normal_quantile_central(p);
    const double x = normal_quantile_tail(std::sqrt(-2.0 * std::log(p < low ? p : 1.0 - p)));
    return p < low ? x : -x;
  }

  /// Φ⁻¹(p) in the lower tail (p < 0.02425) from q = √(−2 ln p): a rational function of q (no
  /// branch, so it vectorises); −Φ⁻¹ of 1 − p in the upper tail.
  static double normal_quantile_tail(double q) {
    static constexpr double c[6] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                                    -2.549732539343734e+00, 4.374664141464968e+00, 2.938163982698783e+00};
    static constexpr double d[4] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00, 3.754408661907416e+00};
    return (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) / ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  }

 private:
  static double to_unit(std::uint64_t w) { return static_cast<double>(w >> 11) * 0x1.0p-53; }

  void normal_block(std::uint64_t step, std::uint64_t a, std::uint64_t b, std::uint64_t m, std::array<double, 4>& z) const {
    const auto w = block(step, a, b, m);
    for (int p = 0; p < 2; ++p) {
      // (0, 1] for the logarithm; [0, 1) for the angle.
      const double u1 = (static_cast<double>(w[2 * p] >> 11) + 1.0) * 0x1.0p-53;
      const double r = std::sqrt(-2.0 * std::log(u1));
      const double phi = 2.0 * M_PI * to_unit(w[2 * p + 1]);
      z[2 * p] = r * std::cos(phi);
      z[2 * p + 1] = r * std::sin(phi);
    }
  }

  r123::Philox4x64::key_type key_;
};

}  // namespace anisodyn

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

  /// The pair draw θ_ij: the same for (i, j) and (j, i).
  double pair_normal(std::uint64_t step, std::uint64_t i, std::uint64_t j, std::uint64_t k = 0) const {
    return normal(step, std::min(i, j), std::max(i, j), k);
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

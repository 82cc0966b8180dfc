#pragma once
// The pair noise θ_ij of DPD (spec 30 §2): a standard normal for each pair and step, the same for
// (i, j) and (j, i), whatever the thread count or the order of the pairs (spec 00 §7).
//
// θ is the normal quantile (KeyedRandom::normal_quantile, Acklam, relative error 1.2×10⁻⁹) of a
// 53-bit uniform from Philox4x32-10 (Salmon et al., SC'11; the Random123 generator) with counter
// (step low word, step high word, min id, max id) and a key drawn from (seed, purpose).
//
// Why Philox4x32 rather than KeyedRandom's Philox4x64: a DPD step draws one θ for each of some
// 10⁵ pairs, and the 32-bit multiplies of Philox4x32 vectorise (eight or sixteen pairs at once)
// where the 64-bit ones do not. normals() draws a batch sixteen pairs at a time (the rounds with
// AVX-512 intrinsics where the compiler targets it, else a loop it vectorises: integer arithmetic,
// the same bits); the one pair of operator() goes through the same code.
//
// Ids must be below 2³² (a configuration of more particles than that is not a DPD run).
#include <cstddef>
#include <cstdint>

namespace anisodyn {

class PairNoise {
 public:
  PairNoise(std::uint64_t seed, std::uint64_t purpose);

  /// θ of the pair (i, j) at `step`.
  double operator()(std::uint64_t step, std::uint32_t i, std::uint32_t j) const {
    double out;
    normals(step, &i, &j, 1, &out);
    return out;
  }
  /// θ of the pairs (a[m], b[m]), m < n, at `step`, into out[m].
  void normals(std::uint64_t step, const std::uint32_t* a, const std::uint32_t* b, std::size_t n, double* out) const;

  std::uint32_t key(int k) const { return key_[k]; }

 private:
  std::uint32_t key_[2];
};

}  // namespace anisodyn

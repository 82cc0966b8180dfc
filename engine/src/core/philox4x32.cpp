#include "anisodyn/core/philox4x32.hpp"

#include "anisodyn/core/keyed_random.hpp"

#if defined(__AVX512F__)
// GCC 12's AVX-512 headers build some intrinsics on an "undefined" register, which -Wuninitialized
// reports once they are inlined (GCC bug 105593): a false alarm here.
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#endif

namespace anisodyn {

namespace {
// Philox4x32 constants (Random123): multipliers and the Weyl key increments.
constexpr std::uint32_t kM0 = 0xD2511F53u, kM1 = 0xCD9E8D57u, kW0 = 0x9E3779B9u, kW1 = 0xBB67AE85u;
constexpr int kRounds = 10;
}  // namespace

void philox4x32_lanes(std::uint32_t* c0, std::uint32_t* c1, std::uint32_t* c2, std::uint32_t* c3, const std::uint32_t key[2]) {
#if defined(__AVX512F__)
  // Sixteen lanes per register; the 32×32→64 products of the even and the odd lanes separately.
  const __m512i m0 = _mm512_set1_epi64(kM0), m1 = _mm512_set1_epi64(kM1);
  constexpr __mmask16 odd = 0xAAAA;
  __m512i x0 = _mm512_loadu_si512(c0), x1 = _mm512_loadu_si512(c1), x2 = _mm512_loadu_si512(c2), x3 = _mm512_loadu_si512(c3);
  std::uint32_t k0 = key[0], k1 = key[1];
  for (int round = 0; round < kRounds; ++round) {
    const __m512i even0 = _mm512_mul_epu32(x0, m0), odd0 = _mm512_mul_epu32(_mm512_srli_epi64(x0, 32), m0);
    const __m512i even1 = _mm512_mul_epu32(x2, m1), odd1 = _mm512_mul_epu32(_mm512_srli_epi64(x2, 32), m1);
    const __m512i hi0 = _mm512_mask_blend_epi32(odd, _mm512_srli_epi64(even0, 32), odd0);
    const __m512i lo0 = _mm512_mask_blend_epi32(odd, even0, _mm512_slli_epi64(odd0, 32));
    const __m512i hi1 = _mm512_mask_blend_epi32(odd, _mm512_srli_epi64(even1, 32), odd1);
    const __m512i lo1 = _mm512_mask_blend_epi32(odd, even1, _mm512_slli_epi64(odd1, 32));
    x0 = _mm512_xor_si512(_mm512_xor_si512(hi1, x1), _mm512_set1_epi32(static_cast<int>(k0)));
    x2 = _mm512_xor_si512(_mm512_xor_si512(hi0, x3), _mm512_set1_epi32(static_cast<int>(k1)));
    x1 = lo1;
    x3 = lo0;
    k0 += kW0;
    k1 += kW1;
  }
  _mm512_storeu_si512(c0, x0);
  _mm512_storeu_si512(c1, x1);
  _mm512_storeu_si512(c2, x2);
  _mm512_storeu_si512(c3, x3);
#else
  // Lane by lane with the rounds unrolled, so that the lane loop is what the compiler vectorises.
  for (std::size_t l = 0; l < kPhiloxLanes; ++l) {
    std::uint32_t x0 = c0[l], x1 = c1[l], x2 = c2[l], x3 = c3[l], k0 = key[0], k1 = key[1];
#pragma GCC unroll 10
    for (int round = 0; round < kRounds; ++round) {
      const std::uint64_t p0 = static_cast<std::uint64_t>(kM0) * x0, p1 = static_cast<std::uint64_t>(kM1) * x2;
      x0 = static_cast<std::uint32_t>(p1 >> 32) ^ x1 ^ k0;
      x2 = static_cast<std::uint32_t>(p0 >> 32) ^ x3 ^ k1;
      x1 = static_cast<std::uint32_t>(p1);
      x3 = static_cast<std::uint32_t>(p0);
      k0 += kW0;
      k1 += kW1;
    }
    c0[l] = x0;
    c1[l] = x1;
    c2[l] = x2;
    c3[l] = x3;
  }
#endif
}

void philox4x32_key(std::uint64_t seed, std::uint64_t purpose, std::uint32_t key[2]) {
  const std::uint64_t k = KeyedRandom(seed, purpose).block(0, 0, 0, 0)[0];
  key[0] = static_cast<std::uint32_t>(k);
  key[1] = static_cast<std::uint32_t>(k >> 32);
}

}  // namespace anisodyn

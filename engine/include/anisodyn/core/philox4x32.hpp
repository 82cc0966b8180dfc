#pragma once
// Philox4x32-10 (Salmon et al., SC'11; the Random123 generator) on sixteen counters at once: the
// batch that the per-pair noise of DPD (core/pair_noise.hpp) and the per-node noise of LB
// (core/node_noise.hpp) draw from. Integer arithmetic only: the AVX-512 path and the lane-by-lane
// one give the same bits.
#include <cstddef>
#include <cstdint>

namespace anisodyn {

inline constexpr std::size_t kPhiloxLanes = 16;

/// Philox4x32-10 of the counters (c0, c1, c2, c3)[l], l < 16, under the key; the four words of
/// each result replace the counter.
void philox4x32_lanes(std::uint32_t* c0, std::uint32_t* c1, std::uint32_t* c2, std::uint32_t* c3, const std::uint32_t key[2]);

/// The two key words of a noise with its own (seed, purpose): a KeyedRandom draw, so that noises of
/// different purposes are independent.
void philox4x32_key(std::uint64_t seed, std::uint64_t purpose, std::uint32_t key[2]);

}  // namespace anisodyn

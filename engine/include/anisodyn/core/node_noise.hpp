#pragma once
// Per-node noise of a lattice (LB, spec 40 §2.3): standard normals addressed by (step, node, k),
// so that any thread may draw any node's numbers and a run gives the same bits on any number of
// threads (spec 00 §7).
//
// Draw k of node n at step s is word k mod 4 of Philox4x32-10 (core/philox4x32.hpp) at counter
// (s low word, s high word, n, k / 4) under a key drawn from (seed, purpose), turned into a normal
// by its quantile: x = Φ⁻¹((w + ½) 2⁻³²) (Acklam's approximation, relative error 1.2×10⁻⁹). One
// 32-bit word per normal, rather than the 53 bits of the DPD pair noise, because a node takes
// fifteen normals per step: the draws are exact quantiles of a 2³²-point grid, so the normal is
// truncated at |x| = 6.34 (a variance short by 10⁻⁸), which the thermal noise of a fluid does
// not see. The tails' logarithm is the file's own, vectorised (within a few ulp of std::log).
//
// Node numbers must be below 2³² (a lattice of more nodes is not a run of this engine).
#include <cstddef>
#include <cstdint>

namespace anisodyn {

class NodeNoise {
 public:
  NodeNoise(std::uint64_t seed, std::uint64_t purpose);

  /// Draws 0 … per_node − 1 of nodes first … first + count − 1 at `step`: draw k of node first + m
  /// into out[k * stride + m] (per_node ≤ 16; stride ≥ count).
  void normals(std::uint64_t step, std::uint32_t first, std::size_t count, int per_node, double* out, std::size_t stride) const;

  /// Draw k of one node (the same value as normals() gives it).
  double operator()(std::uint64_t step, std::uint32_t node, int k) const;

 private:
  std::uint32_t key_[2];
};

}  // namespace anisodyn

#pragma once
// Orientational order from per-axis Q tensors (spec 50 §3.1):
//   Q^{kk} = (1/2N) Σ_i (3 ê_k,i ⊗ ê_k,i − I),  k ∈ {T, W, L} (body axes x, y, z).
// Its largest eigenvalue is the uniaxial order parameter U_k, the eigenvector the director d_k.
#include <array>
#include <vector>

#include "anisodyn/core/types.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn {

struct UniaxialOrder {
  double order = 0.0;             // largest eigenvalue
  Vec3 director = Vec3::UnitZ();  // its eigenvector
  Vec3 eigenvalues = Vec3::Zero();  // ascending
};

/// Q tensor of a set of unit vectors.
Mat3 q_tensor(const std::vector<Vec3>& axes);
UniaxialOrder uniaxial_order(const Mat3& q);

/// Order of body axes T, W, L (index 0, 1, 2) over the particles of one species.
std::array<UniaxialOrder, 3> body_axis_order(const State& state, int species);

/// Phase criterion of spec 50 §3.1: nematic if any U_k exceeds 0.40.
inline constexpr double kNematicThreshold = 0.40;

/// Mean largest eigenvalue of Q for N uniformly random orientations (the finite-N isotropic
/// baseline, O(N^-1/2)), estimated from `samples` independent sets with a fixed seed.
double isotropic_order_baseline(std::size_t n, int samples = 200);

}  // namespace anisodyn

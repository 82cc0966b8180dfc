#pragma once
// Unbounded rotation vectors of a body axis (spec 50 §2.1, B1):
//   φ_λ(t) = Σ_k δφ_k,  δφ_k = (λ̂_k × λ̂_{k+1}/|λ̂_k × λ̂_{k+1}|) arccos(λ̂_k · λ̂_{k+1}).
// DMC trajectories carry the exact sum accumulated at every accepted move (element
// "rotation_vector", 3 axes × 3 components); otherwise it is accumulated between frames, and
// per-frame rotations above 0.2 rad are counted (the frames are then too sparse).
#include <cstddef>
#include <vector>

#include "anisodyn/analysis/trajectory.hpp"

namespace anisodyn::analysis {

inline constexpr double kMaxFrameRotation = 0.2;  // rad (spec 50 §2.1)

struct RotationVectorPath {
  std::vector<double> phi;        // [F × N × 3]
  bool exact = false;             // from the engine's per-move accumulation
  std::size_t violations = 0;     // frame intervals with a rotation > 0.2 rad (frame accumulation only)
  std::size_t intervals = 0;
};

/// The rotation-vector path of body axis `axis` (0, 1, 2) for every particle.
RotationVectorPath rotation_vector_path(const Trajectory& t, int axis);

}  // namespace anisodyn::analysis

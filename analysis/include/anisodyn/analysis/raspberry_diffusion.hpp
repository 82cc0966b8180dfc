#pragma once
// The lag curves of a rigid body's Brownian motion that spec 40 §8 takes its diffusion coefficients
// from, at lags of k = 1 … K frames (uniform frame spacing), each the mean over every origin:
// - lab:   ⟨|X(t + τ) − X(t)|²⟩ of the unwrapped centre (D_t = slope/6, §8.1);
// - vector_angle: ⟨ΔΘ²⟩, ΔΘ = arccos(p̂(t)·p̂(t + τ)) of one body-fixed vector (the reference bead's
//   offset: ⟨ΔΘ²⟩ ≈ 4 D_r τ at small τ, §8.2; the paper's convention divides by 6τ);
// - axes_angle: Σ_i ⟨ΔΘ_i²⟩ over the three body axes (≈ 12 D̄_r τ, the three-axis estimator);
// - body_translation[i]: ⟨(ΔX^b_i)²⟩ along body axis i (§8.3, D_t,i = slope/2);
// - body_rotation[i]: ⟨ΔΘ_i²⟩ about body axis i by the projection method (§8.4, D_r,i = slope/2).
#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "anisodyn/core/types.hpp"

namespace anisodyn::analysis {

struct BodyLagCurves {
  std::vector<double> lab, vector_angle, axes_angle;
  std::array<std::vector<double>, 3> body_translation, body_rotation;

  static constexpr std::size_t kCurves = 9;
  /// The nine curves one after the other (a replica's sample for the jackknife), and back.
  std::vector<double> flatten() const;
  static BodyLagCurves unflatten(const std::vector<double>& flat);
};

/// The curves of one body from its centre and orientation (body → lab) at every frame, for lags
/// 1 … max_lag frames (max_lag < frames); `reference` is the body-fixed vector of vector_angle.
BodyLagCurves body_lag_curves(std::span<const Vec3> centre, std::span<const Quat> orientation, const Vec3& reference, std::size_t max_lag);

/// ⟨|path(t + k) − path(t)|²⟩ per component for k = 1 … max_lag, over every origin.
std::vector<Vec3> component_mean_squares(std::span<const Vec3> path, std::size_t max_lag);

}  // namespace anisodyn::analysis

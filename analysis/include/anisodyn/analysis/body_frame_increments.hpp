#pragma once
// Body-frame increments of a rigid body's trajectory (spec 40 §8.3–8.4), from its unwrapped centre
// X(t_n) and its orientation q(t_n) (body → lab) at frames n = 0 … F − 1; one increment per frame
// interval (t_{n−1}, t_n]:
// - translation: δX^b_n = R(q_mid)ᵀ [X(t_n) − X(t_{n−1})], q_mid the slerp halfway from q(t_{n−1})
//   to q(t_n) (spec 40 §8.3's decision: the orientation at the interval's midpoint);
// - rotation, by projection (§8.4): with î, ĵ, k̂ the body axes in the lab (columns of R(q)),
//   δΘ_x = atan2(k̂_n·ĵ_{n−1}, k̂_n·k̂_{n−1}), δΘ_y = atan2(î_n·k̂_{n−1}, î_n·î_{n−1}),
//   δΘ_z = atan2(ĵ_n·î_{n−1}, ĵ_n·ĵ_{n−1}): −δ for a right-handed turn +δ about that body axis
//   (a common sign, irrelevant for mean squares).
// Summed, they give the body-frame paths X^b and Θ whose mean squares give D_t,i = ⟨ΔX_i^b²⟩/(2τ)
// and D_r,i = ⟨ΔΘ_i²⟩/(2τ).
#include <span>
#include <vector>

#include "anisodyn/core/types.hpp"

namespace anisodyn::analysis {

std::vector<Vec3> body_frame_displacements(std::span<const Vec3> centre, std::span<const Quat> orientation);
std::vector<Vec3> body_frame_rotation_angles(std::span<const Quat> orientation);

/// The running sums: path[0] = 0, path[n] = Σ_{k ≤ n} increment[k − 1].
std::vector<Vec3> accumulate_path(std::span<const Vec3> increments);

}  // namespace anisodyn::analysis

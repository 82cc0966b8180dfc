#pragma once
// Soft overlap-volume repulsion between long thin rods (Tao, den Otter, Padding, Dhont & Briels,
// J. Chem. Phys. 122, 244903 (2005); spec 20 §4, spec 70 §5.2; docs/bd.md). Pair energy Φ = k V_ov,
// with k the hardness (energy per volume), L the rod length, D the bare diameter.
//
// Main branch (sin γ ≥ D/L, sin γ = |û_i × û_j|): V_ov = f(d)/sin γ with
//   f(d) = 4 ∫_{−(D−d)/2}^{(D−d)/2} √((D/2)² − (d/2+p)²) √((D/2)² − (d/2−p)²) dp   (0 for d ≥ D).
// d is the distance between the closest points p_i, p_j of the two finite axis segments
// (SegmentDistance, the default), or of the two infinite lines, counted only when both closest points
// lie on the segments (InteriorOnly).
// Near-parallel branch (sin γ < D/L): V_ov = A_ov(d) L_ov with the lens area
//   A_ov(d) = (D²/2) arccos(d/D) − (d/2)√(D² − d²), L_ov = max(0, L − ½(|r_ij·û_i| + |r_ij·û_j|)),
// r_ij = r_i − r_j, d = |r_ij − (r_ij·ū)ū|, ū = (û_i + σû_j)/|û_i + σû_j|, σ = sign(û_i·û_j).
// The switch between the branches is discontinuous, as published (factor 1.178 at d = 0).
//
// f is a Hermite cubic interpolant of Gauss–Legendre values of f and f′ (one process-wide table,
// built on first use); f_prime() is the exact derivative of that interpolant. Forces and torques are
// the exact gradients of the energy returned: F_i = −∇_{r_i}Φ, T_i = −û_i × ∂Φ/∂û_i.
#include "anisodyn/core/types.hpp"

namespace anisodyn {

/// How the main branch treats the finite rod length (spec 20 §4.1).
enum class FiniteLengthRule { SegmentDistance, InteriorOnly };

struct OverlapVolumeSettings {
  double length = 0.0;    ///< L
  double diameter = 0.0;  ///< bare D (the one in V_ov)
  double hardness = 0.0;  ///< k, energy per volume
  FiniteLengthRule rule = FiniteLengthRule::SegmentDistance;
};

/// One rod pair, as seen from rod i.
struct RodPairTerm {
  bool interacts = false;      ///< V_ov > 0
  bool near_parallel = false;  ///< the branch sin γ < D/L was used
  double energy = 0.0;         ///< Φ_ij = k V_ov (the whole pair energy)
  double distance = 0.0;       ///< d of the branch used (for the histogram of x = d/D); set whenever the
                               ///< centre distance is below cutoff(), meaningful when interacts
  Vec3 force = Vec3::Zero();   ///< F_i = −∇_{r_i}Φ; F_j = −F_i
  Vec3 torque = Vec3::Zero();  ///< T_i = −û_i × ∂Φ/∂û_i; T_j comes from the call with (−r_ji, û_j, û_i)
};

class OverlapVolume {
 public:
  /// Throws std::invalid_argument unless 0 < D < L and k ≥ 0 (all finite).
  explicit OverlapVolume(const OverlapVolumeSettings& settings);

  const OverlapVolumeSettings& settings() const { return s_; }
  /// f(d) and its derivative for the diameter of the settings: the interpolant, and its exact
  /// derivative (both 0 for d ≥ D; d ≥ 0).
  double f(double d) const;
  double f_prime(double d) const;

  /// Pair term for rods i, j with r_ji = r_j − r_i (minimum image) and unit axes û_i, û_j. The call for
/// (−r_ji, û_j, û_i) gives the same energy and exactly −force.
  RodPairTerm operator()(const Vec3& r_ji, const Vec3& u_i, const Vec3& u_j) const;

  /// Centre distance at and beyond which no pair interacts.
  double cutoff() const { return s_.length + s_.diameter; }
  /// Distance between the two axis segments (length L) at and beyond which no pair interacts, for
  /// neighbour lists of segments: D for the main branch (either rule), and a little more for the
  /// near-parallel one, whose pairs have segment distance below √(D² + ε²) with
  /// ε = L sin²(γ_s/2)/cos(γ_s/2) ≈ D²/(4L), sin γ_s = D/L (derived in overlap_volume.cpp).
  double segment_cutoff() const;
  /// k with k f(0.8 D) = kT (= 17.7113 kT/D³; spec 20 §4.2).
  static double hardness_for(double diameter, double kT);

 private:
  OverlapVolumeSettings s_;
};

/// f(xD)/D³ and f′(xD)/D² for 0 ≤ x ≤ 1 by direct Gauss–Legendre quadrature (256 nodes, substitution
/// p = ((D−d)/2) sin t), without the table: the values the table is built from (at x = 0 and
/// x ≥ 3.8×10⁻⁶). Round-off accurate for x = 0 and x ≥ 10⁻⁶; below that the integrand's kink at
/// t = π/2 (width ~√x) is under-resolved (f′ off by 3×10⁻¹¹ at x = 10⁻⁸).
struct OverlapIntegral {
  double f = 0.0, f_prime = 0.0;
};
OverlapIntegral overlap_integral(double x);

/// Size of the published discontinuity at sin γ = D/L. Configurations: û_i = x̂, û_j in the xy-plane
/// at angle γ to x̂, r_ji = (offset, 0, d), so the infinite axes cross at distance d, at the
/// centre of rod j and offset along rod i. Each (d, offset) on a steps × steps grid of
/// [0, d_max] × [0, offset_max] is evaluated at sin γ = (D/L)(1 ± 10⁻⁹); pairs where neither side
/// interacts are skipped. Forces are compared by magnitude.
struct BranchSwitchJump {
  double contact_energy_ratio = 0.0;      ///< E(below)/E(above) at d = 0, offset 0
  double max_relative_energy_jump = 0.0;  ///< max |E₋ − E₊| / max(E₋, E₊)
  double max_relative_force_jump = 0.0;   ///< max ||F₋| − |F₊|| / max(|F₋|, |F₊|)
  double max_energy_jump = 0.0;           ///< max |E₋ − E₊|
  double max_force_jump = 0.0;            ///< max ||F₋| − |F₊||
  double worst_energy_d = 0.0, worst_energy_offset = 0.0;  ///< where the relative energy jump is largest
  double worst_force_d = 0.0, worst_force_offset = 0.0;    ///< where the relative force jump is largest
};
BranchSwitchJump measure_branch_switch_jump(const OverlapVolume& ov, double d_max, double offset_max,
                                            int steps = 100);

}  // namespace anisodyn

#pragma once
// Cuboid–cuboid (and cube–cube) overlap: 15-axis separating-axis test (spec 10 §2.3), the OBB test
// of Gottschalk, Lin & Manocha (1996) as used for hard cuboids by John & Escobedo (2005).
//
// Boxes A and B have half-extents a_k, b_l and unit body axes A_k, B_l (the columns of Ra, Rb);
// t = r_B − r_A (minimum image). In A's frame t_k = t·A_k and R_kl = A_k·B_l. The boxes are
// separated iff one of the 15 candidate axes (3 faces of A, 3 faces of B, 9 edge–edge cross
// products) separates their projections with a strict ">", so touching counts as overlap.
//
// AbsR_kl = |R_kl| + ε with ε = 1e-12 × (largest half-extent of the pair). The guard keeps the
// degenerate cross-product axes of (near-)parallel edges from reporting a spurious separation from
// round-off; it inflates the projections by at most ε·Σ(half-extents) ≈ 1e-11 relative, i.e. it can
// only turn a separation of that order into an overlap, never the reverse.
//
// Order of evaluation: circumsphere rejection and inscribed-sphere acceptance (early exits), then
// the 15 axes — the 6 face axes first, then the 9 edge axes — evaluated without branches and
// combined. On pairs within the circumsphere distance (those a cell list hands over) each test's
// outcome is unpredictable, and exiting at the first separating axis was measured 10–18% slower on
// boards and cubes (bench/overlap_kernels.cpp, Pairs/CuboidCuboid_SAT_early_exit; numbers in
// docs/geometry.md). The circumsphere test is written as a single branch for the same reason:
// "x > 0 && x² > …" adds a data-dependent branch that cost ~8 ns per pair.
#include <algorithm>
#include <cmath>

#include "anisodyn/core/types.hpp"

namespace anisodyn {

/// Relative guard added to |R_kl| (multiplied by the largest half-extent), spec §2.3.
inline constexpr double kSatEpsilon = 1e-12;

/// Separating-axis overlap test of two cuboids.
///   a, b   : half-extents of A and B along their body axes;
///   Ra, Rb : rotation matrices, columns = body axes in the lab frame;
///   t      : r_B − r_A (minimum-imaged), lab frame.
[[nodiscard]] inline bool overlap_cuboid_cuboid(const Vec3& a, const Mat3& Ra, const Vec3& b, const Mat3& Rb,
                                                const Vec3& t) noexcept {
  const double t2 = t.squaredNorm();
  const double ra2 = a.squaredNorm(), rb2 = b.squaredNorm();
  // Circumsphere rejection |t| > ra + rb, without square roots: with x = |t|² − ra² − rb²,
  // |t|² > (ra + rb)² ⇔ x > 2 ra rb ⇔ x > 0 and x² > 4 ra² rb². The factor (1 + 1e-12) keeps
  // round-off from rejecting a circumsphere contact; the SAT below decides those cases.
  // "&" rather than "&&": one predictable branch instead of a data-dependent one on x > 0.
  const double x = t2 - ra2 - rb2;
  if ((x > 0.0) & (x * x > 4.0 * (1.0 + 1e-12) * ra2 * rb2)) return false;
  // Inscribed spheres intersect ⇒ overlap (slightly shrunk for the same reason).
  const double rin = std::min({a[0], a[1], a[2]}) + std::min({b[0], b[1], b[2]});
  if (t2 <= (1.0 - 1e-12) * rin * rin) return true;

  const double eps = kSatEpsilon * std::max({a[0], a[1], a[2], b[0], b[1], b[2]});
  double R[3][3], AR[3][3], tA[3];
  for (int k = 0; k < 3; ++k) {
    tA[k] = Ra(0, k) * t[0] + Ra(1, k) * t[1] + Ra(2, k) * t[2];
    for (int l = 0; l < 3; ++l) {
      R[k][l] = Ra(0, k) * Rb(0, l) + Ra(1, k) * Rb(1, l) + Ra(2, k) * Rb(2, l);
      AR[k][l] = std::abs(R[k][l]) + eps;
    }
  }
  bool separated = false;
  // Face axes of A.
  for (int k = 0; k < 3; ++k)
    separated |= std::abs(tA[k]) > a[k] + b[0] * AR[k][0] + b[1] * AR[k][1] + b[2] * AR[k][2];
  // Face axes of B.
  for (int l = 0; l < 3; ++l) {
    const double tB = tA[0] * R[0][l] + tA[1] * R[1][l] + tA[2] * R[2][l];
    separated |= std::abs(tB) > a[0] * AR[0][l] + a[1] * AR[1][l] + a[2] * AR[2][l] + b[l];
  }
  // Edge–edge axes A_k × B_l (indices mod 3).
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    for (int l = 0; l < 3; ++l) {
      const int l1 = (l + 1) % 3, l2 = (l + 2) % 3;
      const double lhs = std::abs(tA[k2] * R[k1][l] - tA[k1] * R[k2][l]);
      const double rhs = a[k1] * AR[k2][l] + a[k2] * AR[k1][l] + b[l1] * AR[k][l2] + b[l2] * AR[k][l1];
      separated |= lhs > rhs;
    }
  }
  return !separated;
}

}  // namespace anisodyn

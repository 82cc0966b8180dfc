#pragma once
// Hard-ellipsoid overlap (ellipsoid–ellipsoid and ellipsoid–sphere). Contact counts as overlap.
//
// Conventions (as for the other kernels, docs/geometry.md): `semi` holds the semi-axes (all > 0)
// along the body x, y, z axes, which are the columns of R in the lab frame; t = r_b − r_a,
// minimum-imaged; sphere radii are > 0.
//
// Method: the Perram–Wertheim contact function (J. Comput. Phys. 58, 409 (1985))
//     F(λ) = λ(1 − λ) tᵀ G(λ)⁻¹ t,   G(λ) = (1 − λ) P_A + λ P_B,   P = R diag(semi²) Rᵀ,
// is concave on [0, 1] with F(0) = F(1) = 0, and max F = μ², where μ is the factor by which both
// bodies must be scaled about their centres to touch; so the pair overlaps iff max F ≤ 1. Why this
// method: one concave function of one variable to maximise, instead of a quartic's roots or a
// 3-D distance minimisation; and since F ∝ |t|², a relative error ε in F is a relative error ε/2
// in the contact distance along t, whatever the shapes.
//
// Why the polynomial form. Writing each P as a sum of rank-one terms (α_i e_i e_iᵀ for A,
// β_r m_r m_rᵀ for B, with α = a², β = b² and e_i, m_r the body axes), the Cauchy–Binet
// expansions of det G and of tᵀ adj(G) t give, with u = 1 − λ,
//     F(λ) = λ u Q(λ) / P(λ),  Q = q0 u² + q1 u λ + q2 λ²,  P = c0 u³ + c1 u² λ + c2 u λ² + c3 λ³,
//     q0 = Σ α_iα_j (t·e_k)²   q1 = Σ_{i,r} α_i β_r (t·(e_i × m_r))²   q2 = Σ β_rβ_s (t·m_p)²
//     c0 = α1α2α3   c1 = Σ α_iα_j β_r (e_k·m_r)²   c2 = Σ α_i β_rβ_s (e_i·m_p)²   c3 = β1β2β3
// ({i, j, k} and {r, s, p} run over the three axes). Every coefficient is a sum of non-negative
// terms, and so is every evaluation of Q and P on [0, 1]: no cancellation, however elongated or
// nearly parallel the bodies are, and no linear solve. Setting up costs about one 3×3 product;
// each λ then costs a few dozen flops and two divisions (1/P and the Newton step).
//
// Why the maximiser can stop early. F(λ) > 1 at any λ proves separation. Concavity gives an upper
// bound: max F lies below the meeting point of the tangents at any λ_lo < λ* < λ_hi, which proves
// overlap once it is ≤ 1. The tangents at 0 and 1 (slopes s_A = tᵀP_A⁻¹t and −s_B = −tᵀP_B⁻¹t)
// already settle deep overlaps. Otherwise Newton's iteration on F′ (analytic F″), safeguarded by
// bisection of the bracket [λ_lo, λ_hi], starts at λ0 = √s_B / (√s_A + √s_B), the exact maximiser
// for two spheres; about 3 evaluations of F suffice for pairs 10⁻⁹..10⁻² from contact. A pair whose
// max F is 1 to rounding ends when the step stalls, and counts as touching (overlap).
//
// Ellipsoid–sphere uses the same coefficients with β = (r², r², r²) and m_r = e_r.
//
// Circumscribed and inscribed spheres decide the clear cases before any of this.
#include <cmath>
#include <limits>

#include "anisodyn/core/types.hpp"

namespace anisodyn {
namespace detail {

/// F(λ) = λ u Q(λ) / P(λ) with u = 1 − λ, Q = q0 u² + q1 u λ + q2 λ² and
/// P = c0 u³ + c1 u² λ + c2 u λ² + c3 λ³; all coefficients ≥ 0, and c0, c3 > 0 (header comment).
struct PwPolynomial {
  double q0, q1, q2, c0, c1, c2, c3;
};

/// Is max F ≤ 1 on [0, 1]? F is concave with F(0) = F(1) = 0, F′(0) = q0/c0 and F′(1) = −q2/c3.
[[nodiscard]] inline bool pw_max_at_most_one(const PwPolynomial& k) noexcept {
  // Tangents at 0 and 1 meet at height sA sB / (sA + sB), sA = q0/c0, sB = q2/c3.
  if (k.q0 * k.q2 <= k.q0 * k.c3 + k.q2 * k.c0) return true;
  // Bracket [lo, hi] of the maximiser, with F and F′ at both ends for the tangent bound.
  double lo = 0.0, f_lo = 0.0, df_lo = k.q0 / k.c0;
  double hi = 1.0, f_hi = 0.0, df_hi = -k.q2 / k.c3;
  // λ0 = √sB / (√sA + √sB): the maximiser for two spheres.
  const double rA = std::sqrt(k.q0 * k.c3), rB = std::sqrt(k.q2 * k.c0);
  double lam = rB / (rA + rB);
  constexpr int kMaxIterations = 100;
  for (int it = 0; it < kMaxIterations; ++it) {
    const double u = 1.0 - lam, w = lam * u, dw = u - lam;
    const double Q = (k.q0 * u + k.q1 * lam) * u + k.q2 * lam * lam;
    const double dQ = -2.0 * k.q0 * u + k.q1 * dw + 2.0 * k.q2 * lam;
    const double d2Q = 2.0 * (k.q0 - k.q1 + k.q2);
    const double P = ((k.c0 * u + k.c1 * lam) * u + k.c2 * lam * lam) * u + k.c3 * lam * lam * lam;
    const double dP =
        -3.0 * k.c0 * u * u + k.c1 * u * (u - 2.0 * lam) + k.c2 * lam * (2.0 * u - lam) + 3.0 * k.c3 * lam * lam;
    const double d2P = 6.0 * (k.c0 * u + k.c3 * lam) + k.c1 * (2.0 * lam - 4.0 * u) + k.c2 * (2.0 * u - 4.0 * lam);
    const double N = w * Q;  // F = N / P
    if (N > P) return false;
    const double dN = dw * Q + w * dQ, d2N = -2.0 * Q + 2.0 * dw * dQ + w * d2Q;
    const double inv = 1.0 / P;
    const double f = N * inv, df = (dN - f * dP) * inv, d2f = (d2N - 2.0 * df * dP - f * d2P) * inv;
    if (df > 0.0) {
      lo = lam; f_lo = f; df_lo = df;
    } else if (df < 0.0) {
      hi = lam; f_hi = f; df_hi = df;
    } else {
      return true;  // at the maximum, and F ≤ 1 there
    }
    // The tangents at lo and hi meet above the maximum; their meeting height ≤ 1, written without
    // the division by df_lo − df_hi > 0.
    if ((f_lo - 1.0) * (df_lo - df_hi) + df_lo * (f_hi - f_lo - df_hi * (hi - lo)) <= 0.0) return true;
    double next = lam - df / d2f;
    if (!(d2f < 0.0) || !(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == lam || !(hi - lo > 4.0 * std::numeric_limits<double>::epsilon() * hi)) break;
    lam = next;
  }
  return true;  // max F is 1 to within rounding: touching
}

}  // namespace detail

/// Ellipsoid–ellipsoid overlap. semi_a, semi_b: semi-axes along body x, y, z; Ra, Rb: rotation
/// matrices whose columns are the body axes in the lab frame; t = r_b − r_a (already
/// minimum-imaged). Contact counts as overlap.
[[nodiscard]] inline bool overlap_ellipsoid_ellipsoid(const Vec3& semi_a, const Mat3& Ra, const Vec3& semi_b,
                                                      const Mat3& Rb, const Vec3& t) noexcept {
  const double r2 = t.squaredNorm();
  const double outer = semi_a.maxCoeff() + semi_b.maxCoeff();
  if (r2 > outer * outer) return false;
  const double inner = semi_a.minCoeff() + semi_b.minCoeff();
  if (r2 <= inner * inner) return true;

  // Plain scalar loops: GCC leaves Eigen's 3×3 product kernels out of line here, at several ns each.
  double al[3], be[3], ta[3], tb[3], M[3][3];  // M[i][r] = e_i · m_r
  for (int i = 0; i < 3; ++i) {
    al[i] = semi_a[i] * semi_a[i];
    be[i] = semi_b[i] * semi_b[i];
    ta[i] = Ra(0, i) * t[0] + Ra(1, i) * t[1] + Ra(2, i) * t[2];
    tb[i] = Rb(0, i) * t[0] + Rb(1, i) * t[1] + Rb(2, i) * t[2];
    for (int r = 0; r < 3; ++r) M[i][r] = Ra(0, i) * Rb(0, r) + Ra(1, i) * Rb(1, r) + Ra(2, i) * Rb(2, r);
  }
  // Products of two of the three squared semi-axes, indexed by the missing axis.
  const double pa[3] = {al[1] * al[2], al[0] * al[2], al[0] * al[1]};
  const double pb[3] = {be[1] * be[2], be[0] * be[2], be[0] * be[1]};
  detail::PwPolynomial k{0.0, 0.0, 0.0, pa[0] * al[0], 0.0, 0.0, pb[0] * be[0]};
  for (int i = 0; i < 3; ++i) {
    k.q0 += pa[i] * ta[i] * ta[i];
    k.q2 += pb[i] * tb[i] * tb[i];
    for (int r = 0; r < 3; ++r) {
      const double m2 = M[i][r] * M[i][r];
      k.c1 += pa[i] * be[r] * m2;
      k.c2 += al[i] * pb[r] * m2;
    }
  }
  for (int r = 0; r < 3; ++r) {  // t·(e_i × m_r) = (m_r × t)_i in A's frame
    const double v0 = M[1][r] * ta[2] - M[2][r] * ta[1];
    const double v1 = M[2][r] * ta[0] - M[0][r] * ta[2];
    const double v2 = M[0][r] * ta[1] - M[1][r] * ta[0];
    k.q1 += be[r] * (al[0] * v0 * v0 + al[1] * v1 * v1 + al[2] * v2 * v2);
  }
  return detail::pw_max_at_most_one(k);
}

/// Ellipsoid–sphere overlap. semi, R: the ellipsoid as above; radius: the sphere's radius;
/// t = r_sphere − r_ellipsoid. Contact counts as overlap.
[[nodiscard]] inline bool overlap_ellipsoid_sphere(const Vec3& semi, const Mat3& R, double radius,
                                                   const Vec3& t) noexcept {
  const double r2 = t.squaredNorm();
  const double outer = semi.maxCoeff() + radius;
  if (r2 > outer * outer) return false;
  const double inner = semi.minCoeff() + radius;
  if (r2 <= inner * inner) return true;

  // The ellipsoid–ellipsoid coefficients with β = (ρ, ρ, ρ), ρ = r², and M = I.
  double al[3], t2[3];
  for (int i = 0; i < 3; ++i) {
    al[i] = semi[i] * semi[i];
    const double ti = R(0, i) * t[0] + R(1, i) * t[1] + R(2, i) * t[2];
    t2[i] = ti * ti;
  }
  const double rho = radius * radius;
  const double pa[3] = {al[1] * al[2], al[0] * al[2], al[0] * al[1]};
  const double sa[3] = {al[1] + al[2], al[0] + al[2], al[0] + al[1]};
  return detail::pw_max_at_most_one({pa[0] * t2[0] + pa[1] * t2[1] + pa[2] * t2[2],
                                     rho * (sa[0] * t2[0] + sa[1] * t2[1] + sa[2] * t2[2]), rho * rho * r2,
                                     pa[0] * al[0], rho * (pa[0] + pa[1] + pa[2]), rho * rho * (al[0] + al[1] + al[2]),
                                     rho * rho * rho});
}

}  // namespace anisodyn

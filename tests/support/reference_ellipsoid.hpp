#pragma once
// Independent long-double references for the ellipsoid kernels (geometry/ellipsoid_overlap.hpp).
// They share no code with the kernels and do not use the Perram–Wertheim contact function.
//
// Ellipsoid–ellipsoid: the algebraic condition of Wang, Wang & Kim, "An algebraic condition for the
// separation of two ellipsoids", CAGD 18, 531 (2001). Each body is a quadric Xᵀ Q X ≤ 0 in
// homogeneous coordinates X = (x, 1), negative inside. The characteristic quartic
//     f(λ) = det(λ A + B)
// always has two negative roots; the bodies are separated iff f has two distinct positive roots,
// and touch iff it has a positive double root. The sign convention matters, as det(λA − B) has the
// opposite roots. Example: for the unit sphere A, |x|² − 1 ≤ 0, and the sphere B, |x − c|² − r² ≤ 0
// with |c| = d, f has the double root −1 and the roots of λ² − (d² − 1 − r²) λ + r², which are
// positive and distinct iff d > 1 + r (the closed-form tests in test_ellipsoid_overlap.cpp check the
// reference on sphere pairs). Since f(0) = det B < 0 and the leading coefficient det A < 0, there
// are 0 or 2 roots with Re λ > 0: none, or a complex pair, means overlap; two reals, separation.
//   Computation: the congruence y = diag(1/a) Raᵀ x only multiplies f by a positive constant, so
// the roots are those of the pair in the frame where A is the unit sphere, A = diag(1, 1, 1, −1).
// The coefficient of λ^k is then a signed sum of the principal minors of B of order 4 − k, all in
// long double. The roots come from Aberth–Ehrlich simultaneous iteration in complex arithmetic
// (double from a circle of starting points, then long double), each root frozen once |f| is at the
// rounding level of its evaluation; they are checked against Vieta's sum. The pair with Re λ > 0
// is classified by its discriminant (λ1 − λ2)² relative to (λ1 + λ2)²: above +kRootPairGap two
// reals, below −kRootPairGap a complex pair, in between (a near-double root) unclear.
//
// Ellipsoid–sphere: the Euclidean distance from the sphere centre to the solid ellipsoid. For a
// centre x outside (body frame), the nearest point is y_k = a_k² x_k / (a_k² + s), where the
// Lagrange multiplier s > 0 is the root of Σ (a_k x_k / (a_k² + s))² = 1; the left side is convex
// and decreasing in s, so Newton's iteration from s = 0 climbs monotonically to the root.
//
// Three-way verdicts as in reference_overlap.hpp: every body is grown and shrunk by η (semi-axes
// and radius ± η; an ellipsoid with semi-axes a ± η lies within Hausdorff distance η of the
// original). Overlap if the shrunk bodies overlap, Separated if the grown ones are separated,
// otherwise Indeterminate; for the algebraic criterion also when a root pattern is unclear. The
// default η is kBandRelative × (sum of the smallest semi-axes or radii).
#include <array>
#include <cmath>
#include <limits>

#include "anisodyn/core/types.hpp"
#include "reference_overlap.hpp"

namespace anisodyn::reference {

/// Relative size of the discriminant of the positive root pair below which its pattern is unclear.
inline constexpr LD kRootPairGap = 1e-14L;

// ---- complex arithmetic, written out (std::complex calls slow library routines) -----------------

template <typename T>
struct Complex {
  T re, im;
};
template <typename T>
Complex<T> operator+(Complex<T> a, Complex<T> b) { return {a.re + b.re, a.im + b.im}; }
template <typename T>
Complex<T> operator-(Complex<T> a, Complex<T> b) { return {a.re - b.re, a.im - b.im}; }
template <typename T>
Complex<T> operator*(Complex<T> a, Complex<T> b) { return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re}; }
template <typename T>
T norm2(Complex<T> a) { return a.re * a.re + a.im * a.im; }
template <typename T>
Complex<T> inverse(Complex<T> a) {
  const T d = 1 / norm2(a);
  return {a.re * d, -a.im * d};
}
using Cx = Complex<LD>;

// ---- the characteristic quartic ------------------------------------------------------------------

/// Coefficients e[k] of λ^k in f(λ) = det(λA + B) for ellipsoid A (semi-axes a, axes Ra) at the
/// origin and B (b, Rb) at t, in the frame where A is the unit sphere.
inline std::array<LD, 5> wwk_quartic(const V3& a, const M3& Ra, const V3& b, const M3& Rb, const V3& t) {
  // y = diag(1/a) Raᵀ x. B becomes (y − c)ᵀ K (y − c) ≤ 1 with K = W Wᵀ,
  // W(i, r) = a_i (Ra_i · Rb_r) / b_r, and centre c = diag(1/a) Raᵀ t.
  M3 W;
  for (int i = 0; i < 3; ++i)
    for (int r = 0; r < 3; ++r) W[i][r] = a[i] * dot(column(Ra, i), column(Rb, r)) / b[r];
  const V3 tb = to_body(Ra, t);
  const V3 c{tb[0] / a[0], tb[1] / a[1], tb[2] / a[2]};
  // Homogeneous matrix of B: [[K, −K c], [−cᵀK, cᵀK c − 1]].
  LD H[4][4];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) H[i][j] = W[i][0] * W[j][0] + W[i][1] * W[j][1] + W[i][2] * W[j][2];
  LD cKc = 0;
  for (int i = 0; i < 3; ++i) {
    const LD Kc = H[i][0] * c[0] + H[i][1] * c[1] + H[i][2] * c[2];
    H[i][3] = H[3][i] = -Kc;
    cKc += c[i] * Kc;
  }
  H[3][3] = cKc - 1;

  const auto m2 = [&](int i, int j) { return H[i][i] * H[j][j] - H[i][j] * H[j][i]; };
  const auto m3 = [&](int i, int j, int k) {
    return H[i][i] * (H[j][j] * H[k][k] - H[j][k] * H[k][j]) - H[i][j] * (H[j][i] * H[k][k] - H[j][k] * H[k][i]) +
           H[i][k] * (H[j][i] * H[k][j] - H[j][j] * H[k][i]);
  };
  // det B by Laplace expansion in the 2×2 minors of rows (0, 1) and the complementary ones of (2, 3).
  const auto minor2 = [&](int r0, int c0, int c1) { return H[r0][c0] * H[r0 + 1][c1] - H[r0][c1] * H[r0 + 1][c0]; };
  constexpr int kPairs[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  LD d4 = 0;
  for (int p = 0; p < 6; ++p) {
    const int q = 5 - p;                         // the complementary column pair
    const LD sign = (p == 1 || p == 4) ? -1 : 1;  // (−1)^(1 + j + k) for columns j < k
    d4 += sign * minor2(0, kPairs[p][0], kPairs[p][1]) * minor2(2, kPairs[q][0], kPairs[q][1]);
  }
  // f(λ) = Σ_S λ^|S| Π_{i∈S} d_i · det B[S̄, S̄] with d = (1, 1, 1, −1).
  std::array<LD, 5> e;
  e[4] = -1;
  e[3] = H[3][3] - (H[0][0] + H[1][1] + H[2][2]);
  e[2] = m2(0, 3) + m2(1, 3) + m2(2, 3) - (m2(0, 1) + m2(0, 2) + m2(1, 2));
  e[1] = m3(1, 2, 3) + m3(0, 2, 3) + m3(0, 1, 3) - m3(0, 1, 2);
  e[0] = d4;
  return e;
}

/// Aberth–Ehrlich iteration in T arithmetic on the monic quartic Σ q[j] w^j (q[4] = 1), from the
/// distinct points w. A point is frozen once |q(w)| is at the rounding level of its evaluation, or
/// once its correction is at the rounding level of w.
template <typename T>
void aberth(const std::array<T, 5>& q, std::array<Complex<T>, 4>& w) {
  std::array<bool, 4> frozen{};
  constexpr T eps = std::numeric_limits<T>::epsilon();
  for (int it = 0; it < 500; ++it) {
    bool moving = false;
    for (int k = 0; k < 4; ++k) {
      if (frozen[k]) continue;
      Complex<T> p{1, 0}, dp{0, 0};
      const T m = std::sqrt(norm2(w[k]));
      T bound = 1;  // Σ |q_j| m^j, bounds the rounding of the Horner sum
      for (int j = 3; j >= 0; --j) {
        dp = dp * w[k] + p;
        p = p * w[k] + Complex<T>{q[j], 0};
        bound = bound * m + std::abs(q[j]);
      }
      bound *= 16 * eps;
      if (norm2(p) <= bound * bound) {
        frozen[k] = true;
        continue;
      }
      Complex<T> S{0, 0};
      for (int j = 0; j < 4; ++j)
        if (j != k) S = S + inverse(w[k] - w[j]);
      const Complex<T> N = p * inverse(dp);
      const Complex<T> step = N * inverse(Complex<T>{1, 0} - N * S);
      w[k] = w[k] - step;
      if (norm2(step) <= 4 * eps * eps * norm2(w[k])) frozen[k] = true;
      else moving = true;
    }
    if (!moving) break;
  }
}

/// The four complex roots of Σ e[k] λ^k (e[4] ≠ 0). Cold: Aberth in double from points on a circle,
/// then in long double from there; warm (`start`, the roots of a nearby quartic): long double only.
inline std::array<Cx, 4> quartic_roots(const std::array<LD, 5>& e, const std::array<Cx, 4>* start = nullptr) {
  // Monic and rescaled, w = λ / ρ, so that the product of the roots has modulus 1.
  std::array<LD, 5> q;
  for (int k = 0; k < 5; ++k) q[k] = e[k] / e[4];
  const LD rho = std::sqrt(std::sqrt(std::abs(q[0])));
  LD s = 1;
  for (int k = 3; k >= 0; --k) {
    s *= rho;
    q[k] /= s;
  }
  std::array<Cx, 4> w;
  if (start) {
    for (int k = 0; k < 4; ++k) w[k] = {(*start)[k].re / rho, (*start)[k].im / rho};
  } else {
    // e^{i(0.4 + kπ/2)}: on the unit circle, off the real axis and not conjugate pairs.
    constexpr double c = 0.921060994002885, sn = 0.389418342308651;  // cos 0.4, sin 0.4
    std::array<Complex<double>, 4> wd{Complex<double>{c, sn}, {-sn, c}, {-c, -sn}, {sn, -c}};
    std::array<double, 5> qd;
    for (int k = 0; k < 5; ++k) qd[k] = double(q[k]);
    aberth(qd, wd);
    for (int k = 0; k < 4; ++k) w[k] = {wd[k].re, wd[k].im};
  }
  for (int k = 1; k < 4; ++k)  // Aberth needs distinct points: nudge a repeated one off the axis
    for (int j = 0; j < k; ++j)
      if (norm2(w[k] - w[j]) <= 1e-24L * norm2(w[k])) w[k].im += 1e-6L * std::sqrt(norm2(w[k]));
  aberth(q, w);
  for (auto& z : w) z = {z.re * rho, z.im * rho};
  return w;
}

enum class RootPattern { NoPositivePair, TwoPositiveRoots, Unclear };

/// Positive-root pattern of the WWK quartic e with roots z (see the header comment).
inline RootPattern positive_root_pattern(const std::array<LD, 5>& e, const std::array<Cx, 4>& z) {
  // Vieta: the roots sum to −e3/e4. A violation means two approximations found the same root and
  // missed another (an O(1) error); the members of a double root are only good to √ε each.
  LD sum = 0, sum_abs = 0;
  for (const Cx& r : z) {
    sum += r.re;
    sum_abs += std::sqrt(norm2(r));
  }
  if (std::abs(sum + e[3] / e[4]) > 1e-6L * sum_abs) return RootPattern::Unclear;
  Cx pos[4];
  int n = 0;
  for (const Cx& r : z)
    if (r.re > 0) pos[n++] = r;
  if (n == 0) return RootPattern::NoPositivePair;
  if (n != 2) return RootPattern::Unclear;
  const LD sp = pos[0].re + pos[1].re;
  if (std::abs(pos[0].im + pos[1].im) > 1e-12L * sp) return RootPattern::Unclear;  // not a conjugate pair
  const Cx d = pos[0] - pos[1];
  const LD disc = (d * d).re / (sp * sp);
  if (disc > kRootPairGap) return RootPattern::TwoPositiveRoots;
  if (disc < -kRootPairGap) return RootPattern::NoPositivePair;
  return RootPattern::Unclear;
}

inline V3 grown(const V3& a, LD g) { return {a[0] + g, a[1] + g, a[2] + g}; }

/// Ellipsoid–ellipsoid verdict, kernel conventions (t = r_b − r_a, columns of R are body axes).
/// eta < 0 selects the default band.
inline Verdict ellipsoid_ellipsoid(const Vec3& semi_a, const Mat3& Ra, const Vec3& semi_b, const Mat3& Rb,
                                   const Vec3& t, double eta = -1.0) {
  const V3 a = ld(semi_a), b = ld(semi_b), tl = ld(t);
  const M3 ra = ld(Ra), rb = ld(Rb);
  const LD e = eta >= 0 ? LD(eta) : LD(kBandRelative) * (LD(semi_a.minCoeff()) + LD(semi_b.minCoeff()));
  const std::array<LD, 5> f_shrunk = wwk_quartic(grown(a, -e), ra, grown(b, -e), rb, tl);
  const std::array<Cx, 4> z_shrunk = quartic_roots(f_shrunk);
  if (positive_root_pattern(f_shrunk, z_shrunk) == RootPattern::NoPositivePair) return Verdict::Overlap;
  // The grown pair's roots are close to the shrunk pair's: start from those.
  const std::array<LD, 5> f_grown = wwk_quartic(grown(a, e), ra, grown(b, e), rb, tl);
  if (positive_root_pattern(f_grown, quartic_roots(f_grown, &z_shrunk)) == RootPattern::TwoPositiveRoots)
    return Verdict::Separated;
  return Verdict::Indeterminate;
}

// ---- ellipsoid–point distance ---------------------------------------------------------------------

/// Euclidean distance from p (relative to the centre, lab frame) to the solid ellipsoid.
inline LD ellipsoid_point_distance(const V3& semi, const M3& R, const V3& p) {
  const V3 x = to_body(R, p);
  LD inside = 0;
  for (int k = 0; k < 3; ++k) inside += (x[k] / semi[k]) * (x[k] / semi[k]);
  if (inside <= 1) return 0;
  // g(s) = Σ (a_k x_k / (a_k² + s))² − 1 is convex and decreasing, and g(0) > 0 outside: Newton's
  // iteration from s = 0 stays left of the root and climbs to it, until rounding stops the climb.
  LD s = 0;
  for (int it = 0; it < 1000; ++it) {
    LD g = -1, dg = 0;
    for (int k = 0; k < 3; ++k) {
      const LD inv = 1 / (semi[k] * semi[k] + s);
      const LD v = semi[k] * x[k] * inv;
      g += v * v;
      dg -= 2 * v * v * inv;
    }
    const LD next = s - g / dg;
    if (!(next > s)) break;
    s = next;
  }
  LD d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const LD v = x[k] * s / (semi[k] * semi[k] + s);
    d2 += v * v;
  }
  return std::sqrt(d2);
}

/// Ellipsoid–sphere verdict, kernel conventions (t = r_sphere − r_ellipsoid).
inline Verdict ellipsoid_sphere(const Vec3& semi, const Mat3& R, double radius, const Vec3& t, double eta = -1.0) {
  const LD e = eta >= 0 ? LD(eta) : LD(kBandRelative) * (LD(semi.minCoeff()) + LD(radius));
  const LD d = ellipsoid_point_distance(ld(semi), ld(R), ld(t));
  return verdict_from_distance(d * d, LD(radius), e);
}

}  // namespace anisodyn::reference

#pragma once
// Independent references for the overlap-volume rod potential (interactions/overlap_volume.hpp),
// written differently from the kernel and evaluated in long double:
//   f(d)   : the geometric form f(d) = ∫_{d−R}^{R} w₁(z) w₂(z) dz, with strip widths
//            w₁ = 2√(R² − z²), w₂ = 2√(R² − (z − d)²) (R = D/2), by tanh–sinh quadrature; the
//            distances to the end points are formed from 1 ∓ tanh directly, so the square roots
//            keep full relative accuracy there;
//   f′(d)  : ∫ w₁ ∂w₂/∂d dz (the boundary term vanishes since w₂(d − R) = 0), same rule;
//   closest points of two segments: the interior stationary point if it lies in the square
//            |a|, |b| ≤ L/2, else the best of the four edges (each a clamped one-dimensional
//            minimisation); returns which parameters sit on the boundary;
//   pair energy: V_ov of both branches and both finite-length rules from these pieces.
#include <algorithm>
#include <array>
#include <cmath>

#include "anisodyn/core/types.hpp"
#include "anisodyn/interactions/overlap_volume.hpp"

namespace anisodyn::reference {

using LD = long double;

namespace detail {

// ∫_{lo}^{hi} g(x_lo, x_hi) dx by tanh–sinh with step `step`, where g receives the distances of the
// node from both ends (exact near the ends).
template <class G>
LD tanh_sinh(LD lo, LD hi, G&& g, LD step) {
  const LD half = 0.5L * (hi - lo), pi_2 = 0.5L * 3.14159265358979323846264338327950288L;
  LD sum = 0.0L;
  for (int k = -static_cast<int>(4.5L / step); k <= static_cast<int>(4.5L / step); ++k) {
    const LD tau = k * step, y = pi_2 * std::sinh(tau), e = std::exp(-2.0L * std::fabs(y));
    const LD near = 2.0L * e / (1.0L + e), far = 2.0L / (1.0L + e);  // 1 − |x|, 1 + |x|
    const LD from_hi = half * (y >= 0.0L ? near : far), from_lo = half * (y >= 0.0L ? far : near);
    const LD ch = std::cosh(y), weight = pi_2 * std::cosh(tau) / (ch * ch);
    if (from_hi <= 0.0L || from_lo <= 0.0L) continue;
    sum += weight * g(from_lo, from_hi);
  }
  return sum * step * half;
}

}  // namespace detail

/// f(xD)/D³, 0 ≤ x ≤ 1.
inline LD overlap_f(LD x, LD step = 1.0L / 64.0L) {
  if (x >= 1.0L) return 0.0L;
  const LD R = 0.5L;  // z runs over [x − R, R]
  return detail::tanh_sinh(x - R, R, [&](LD from_lo, LD from_hi) {
    // from_hi = R − z; from_lo = z − (x − R) = R + (z − x).
    const LD w1 = 2.0L * std::sqrt(from_hi * (2.0L * R - from_hi));
    const LD w2 = 2.0L * std::sqrt(from_lo * (2.0L * R - from_lo));
    return w1 * w2;
  }, step);
}

/// f′(xD)/D², 0 ≤ x ≤ 1.
inline LD overlap_f_prime(LD x, LD step = 1.0L / 64.0L) {
  if (x >= 1.0L) return 0.0L;
  const LD R = 0.5L;
  return detail::tanh_sinh(x - R, R, [&](LD from_lo, LD from_hi) {
    const LD w1 = 2.0L * std::sqrt(from_hi * (2.0L * R - from_hi));
    const LD z_minus_x = from_lo - R;  // ∂w₂/∂x = 2(z − x)/√(R² − (z − x)²)
    return w1 * 2.0L * z_minus_x / std::sqrt(from_lo * (2.0L * R - from_lo));
  }, step);
}

using V3 = std::array<LD, 3>;
inline V3 to_ld(const Vec3& v) { return {v[0], v[1], v[2]}; }
inline LD dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline V3 combine(LD x, const V3& a, LD y, const V3& b, LD z, const V3& c) {
  return {x * a[0] + y * b[0] + z * c[0], x * a[1] + y * b[1] + z * c[1], x * a[2] + y * b[2] + z * c[2]};
}

/// Closest points r_i + a û_i and r_j + b û_j; `side_a`, `side_b` = −1, 0, +1 for a parameter at −L/2,
/// inside, at +L/2 (segments), or for the lines: whether the parameter lies outside the segment.
struct ClosestPoints {
  LD a = 0.0L, b = 0.0L, d = 0.0L;
  int side_a = 0, side_b = 0;
};

inline LD distance_at(const V3& t, const V3& ui, const V3& uj, LD a, LD b) {
  const V3 w = combine(a, ui, -b, uj, -1.0L, t);
  return std::sqrt(dot(w, w));
}

inline ClosestPoints line_closest(const Vec3& r_ji, const Vec3& u_i, const Vec3& u_j, LD half) {
  const V3 t = to_ld(r_ji), ui = to_ld(u_i), uj = to_ld(u_j);
  const V3 n = cross(ui, uj);
  const LD den = dot(n, n), c = dot(ui, uj), ti = dot(t, ui), tj = dot(t, uj);
  ClosestPoints p;
  p.a = (ti - c * tj) / den;
  p.b = (c * ti - tj) / den;
  p.d = distance_at(t, ui, uj, p.a, p.b);
  p.side_a = p.a > half ? 1 : p.a < -half ? -1 : 0;
  p.side_b = p.b > half ? 1 : p.b < -half ? -1 : 0;
  return p;
}

inline ClosestPoints segment_closest(const Vec3& r_ji, const Vec3& u_i, const Vec3& u_j, LD half) {
  ClosestPoints line = line_closest(r_ji, u_i, u_j, half);
  if (line.side_a == 0 && line.side_b == 0) return line;
  const V3 t = to_ld(r_ji), ui = to_ld(u_i), uj = to_ld(u_j);
  const LD c = dot(ui, uj), ti = dot(t, ui), tj = dot(t, uj);
  ClosestPoints best;
  best.d = -1.0L;
  auto consider = [&](LD a, LD b) {
    const LD d = distance_at(t, ui, uj, a, b);
    if (best.d < 0.0L || d < best.d) {
      best.a = a;
      best.b = b;
      best.d = d;
    }
  };
  for (const LD edge : {-half, half}) {
    consider(edge, std::clamp(c * edge - tj, -half, half));  // a on an edge: best b
    consider(std::clamp(ti + c * edge, -half, half), edge);  // b on an edge: best a
  }
  best.side_a = best.a >= half ? 1 : best.a <= -half ? -1 : 0;
  best.side_b = best.b >= half ? 1 : best.b <= -half ? -1 : 0;
  return best;
}

/// Lens area of two discs of diameter D at centre distance d.
inline LD lens_area(LD d, LD D) {
  if (d >= D) return 0.0L;
  const LD R = 0.5L * D, half_chord = std::sqrt(R * R - 0.25L * d * d);
  // Two circular segments of half-angle θ = arccos(d/D): R²(θ − sin θ cos θ) each.
  const LD theta = std::atan2(half_chord, 0.5L * d);
  return 2.0L * R * R * theta - d * half_chord;
}

/// Φ_ij / k (= V_ov) for the settings (hardness ignored).
inline LD overlap_volume(const OverlapVolumeSettings& s, const Vec3& r_ji, const Vec3& u_i, const Vec3& u_j) {
  const LD L = s.length, D = s.diameter, half = 0.5L * L;
  const V3 t = to_ld(r_ji), ui = to_ld(u_i), uj = to_ld(u_j);
  const V3 n = cross(ui, uj);
  const LD sin_g = std::sqrt(dot(n, n));
  if (sin_g >= D / L) {
    const ClosestPoints p = s.rule == FiniteLengthRule::SegmentDistance ? segment_closest(r_ji, u_i, u_j, half)
                                                                        : line_closest(r_ji, u_i, u_j, half);
    if (s.rule == FiniteLengthRule::InteriorOnly && (p.side_a != 0 || p.side_b != 0)) return 0.0L;
    return D * D * D * overlap_f(p.d / D) / sin_g;
  }
  const LD sigma = dot(ui, uj) >= 0.0L ? 1.0L : -1.0L;
  V3 axis = combine(1.0L, ui, sigma, uj, 0.0L, uj);
  const LD norm = std::sqrt(dot(axis, axis));
  for (LD& x : axis) x /= norm;
  const V3 r = combine(-1.0L, t, 0.0L, t, 0.0L, t);
  const V3 perp = cross(axis, r);  // |ū × r| is the perpendicular distance
  const LD d = std::sqrt(dot(perp, perp));
  const LD overlap_length = L - 0.5L * (std::fabs(dot(r, ui)) + std::fabs(dot(r, uj)));
  if (overlap_length <= 0.0L) return 0.0L;
  return lens_area(d, D) * overlap_length;
}

}  // namespace anisodyn::reference

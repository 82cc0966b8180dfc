#pragma once
// Independent exact overlap references for testing the geometry kernels (docs/geometry.md).
//
// Written deliberately differently from the kernels and evaluated in long double:
//   sphere–sphere          : |t|² against the squared sum of radii;
//   cuboid–sphere          : closest point by clamping the body-frame coordinates of the centre;
//   cuboid–cuboid          : edge clipping. Two convex polyhedra intersect iff some edge of one
//                            meets the other solid (a vertex of the convex set A∩B lies on two
//                            facet planes of the same body, hence on one of its edges). Each of
//                            the 24 edges is clipped (Liang–Barsky) against the slabs of the other
//                            box in that box's frame;
//   spherocylinder–sphere  : golden-section minimisation of the (convex) squared distance from the
//                            centre to the axis segment, after a coarse scan;
//   spherocylinder pair    : golden-section minimisation over the parameter of segment A of the
//                            (convex) distance from the point to segment B, after a coarse scan.
//
// Three-way verdict. Each body is grown by η and shrunk by η (cuboid half-extents and radii ± η;
// for a cuboid pair the second box by ± 2η, see cuboid_cuboid()).
// If the shrunk bodies overlap the pair overlaps; if the grown bodies are separated it is
// separated; otherwise the pair lies within ~η of contact and is Indeterminate: a kernel may
// answer either way there (round-off, the SAT ε guard), and the tests count such pairs instead of
// comparing them. The default η is kBandRelative × (sum of the inscribed radii).
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "anisodyn/core/types.hpp"
#include "anisodyn/geometry/shape.hpp"

namespace anisodyn::reference {

using LD = long double;
using V3 = std::array<LD, 3>;
/// m[i][k] = lab component i of body axis k (the same indexing as Mat3(i, k)).
using M3 = std::array<std::array<LD, 3>, 3>;

enum class Verdict { Separated, Overlap, Indeterminate };

inline const char* verdict_name(Verdict v) {
  switch (v) {
    case Verdict::Separated: return "separated";
    case Verdict::Overlap: return "overlap";
    case Verdict::Indeterminate: return "indeterminate";
  }
  return "?";
}

/// Band half-width relative to the sum of the inscribed radii of the pair.
inline constexpr double kBandRelative = 1e-10;

inline V3 ld(const Vec3& v) { return {v[0], v[1], v[2]}; }
inline M3 ld(const Mat3& m) {
  M3 r;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) r[i][k] = m(i, k);
  return r;
}
inline V3 column(const M3& m, int k) { return {m[0][k], m[1][k], m[2][k]}; }
inline LD dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline V3 add(const V3& a, const V3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline V3 scale(LD s, const V3& a) { return {s * a[0], s * a[1], s * a[2]}; }
inline LD norm2(const V3& a) { return dot(a, a); }
/// Coordinates of the lab vector v along the body axes of m.
inline V3 to_body(const M3& m, const V3& v) {
  return {dot(column(m, 0), v), dot(column(m, 1), v), dot(column(m, 2), v)};
}

// ---- cuboid–point: closest point by clamping in the body frame ----------------------------------

/// Squared distance from the point p (relative to the cuboid centre, lab frame) to the cuboid.
inline LD cuboid_point_dist2(const V3& half, const M3& R, const V3& p) {
  const V3 q = to_body(R, p);
  V3 closest;
  for (int k = 0; k < 3; ++k) closest[k] = std::clamp(q[k], -half[k], half[k]);
  return norm2(sub(q, closest));
}

// ---- cuboid–cuboid: edge clipping ---------------------------------------------------------------

/// Liang–Barsky: does the segment p0 + λ d, λ ∈ [0, 1], meet the closed box |x_k| ≤ h_k?
inline bool segment_meets_box(const V3& p0, const V3& d, const V3& h) {
  LD lo = 0, hi = 1;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0) {
      if (p0[k] < -h[k] || p0[k] > h[k]) return false;
      continue;
    }
    LD l1 = (-h[k] - p0[k]) / d[k], l2 = (h[k] - p0[k]) / d[k];
    if (l1 > l2) std::swap(l1, l2);
    lo = std::max(lo, l1);
    hi = std::min(hi, l2);
    if (lo > hi) return false;
  }
  return true;
}

/// Does one of the 12 edges of box B (half-extents hb, axes Rb, centre cb) meet the solid box A?
inline bool some_edge_meets(const V3& ha, const M3& Ra, const V3& ca, const V3& hb, const M3& Rb, const V3& cb) {
  const V3 c = to_body(Ra, sub(cb, ca));
  std::array<V3, 3> e;  // half-edge vectors of B in A's frame
  for (int l = 0; l < 3; ++l) e[l] = scale(hb[l], to_body(Ra, column(Rb, l)));
  for (int l = 0; l < 3; ++l) {
    const int l1 = (l + 1) % 3, l2 = (l + 2) % 3;
    for (int s1 = -1; s1 <= 1; s1 += 2)
      for (int s2 = -1; s2 <= 1; s2 += 2) {
        const V3 mid = add(c, add(scale(s1, e[l1]), scale(s2, e[l2])));
        if (segment_meets_box(sub(mid, e[l]), scale(2, e[l]), ha)) return true;
      }
  }
  return false;
}

inline bool boxes_intersect(const V3& ha, const M3& Ra, const V3& hb, const M3& Rb, const V3& t) {
  const V3 zero{0, 0, 0};
  return some_edge_meets(ha, Ra, zero, hb, Rb, t) || some_edge_meets(hb, Rb, t, ha, Ra, zero);
}

// ---- segments: brute-force convex minimisation --------------------------------------------------

/// Minimum of a convex function on [lo, hi]: coarse scan, then golden-section search in the
/// bracket around the best sample. Returns the smallest value evaluated.
template <typename F>
LD convex_min(F&& f, LD lo, LD hi) {
  if (!(hi > lo)) return f(lo);
  constexpr int kScan = 16;
  LD best = f(lo);
  int ibest = 0;
  for (int i = 1; i <= kScan; ++i) {
    const LD v = f(lo + (hi - lo) * i / kScan);
    if (v < best) { best = v; ibest = i; }
  }
  LD a = lo + (hi - lo) * std::max(ibest - 1, 0) / kScan;
  LD b = lo + (hi - lo) * std::min(ibest + 1, kScan) / kScan;
  const LD inv_phi = (std::sqrt(5.0L) - 1) / 2;
  LD c = b - inv_phi * (b - a), d = a + inv_phi * (b - a);
  LD fc = f(c), fd = f(d);
  for (int it = 0; it < 100 && b - a > 0; ++it) {
    if (fc <= fd) {
      b = d; d = c; fd = fc;
      c = b - inv_phi * (b - a); fc = f(c);
    } else {
      a = c; c = d; fc = fd;
      d = a + inv_phi * (b - a); fd = f(d);
    }
    best = std::min({best, fc, fd});
  }
  return best;
}

/// Squared distance from point p to the segment {s u : |s| ≤ h}, by minimising over s.
inline LD point_segment_dist2(const V3& u, LD h, const V3& p) {
  return convex_min([&](LD s) { return norm2(sub(p, scale(s, u))); }, -h, h);
}

/// Squared distance between segments {s uA : |s| ≤ hA} and {t + τ uB : |τ| ≤ hB}: the distance
/// from the point s uA to segment B (closed form, exact for a segment) is convex in s; minimise it.
inline LD segment_segment_dist2(const V3& uA, LD hA, const V3& uB, LD hB, const V3& t) {
  const auto dist_to_B = [&](LD s) {
    const V3 q = sub(scale(s, uA), t);
    const LD tau = std::clamp(dot(q, uB) / dot(uB, uB), -hB, hB);
    return norm2(sub(q, scale(tau, uB)));
  };
  return convex_min(dist_to_B, -hA, hA);
}

// ---- three-way verdicts -------------------------------------------------------------------------

/// Verdict from a centre distance² d2 and a contact radius s (sum of radii), each body ± eta.
inline Verdict verdict_from_distance(LD d2, LD s, LD eta) {
  const LD shrunk = s - 2 * eta, grown = s + 2 * eta;
  if (shrunk >= 0 && d2 <= shrunk * shrunk) return Verdict::Overlap;
  if (d2 > grown * grown) return Verdict::Separated;
  return Verdict::Indeterminate;
}

inline Verdict sphere_sphere(LD ra, LD rb, const V3& t, LD eta) {
  return verdict_from_distance(norm2(t), ra + rb, eta);
}

/// Cuboid at the origin, sphere of radius rs at p.
inline Verdict cuboid_sphere(const V3& half, const M3& R, LD rs, const V3& p, LD eta) {
  const auto overlaps = [&](LD g) {
    const V3 h{half[0] + g, half[1] + g, half[2] + g};
    const LD r = rs + g;
    return cuboid_point_dist2(h, R, p) <= r * r;
  };
  if (overlaps(-eta)) return Verdict::Overlap;
  if (!overlaps(eta)) return Verdict::Separated;
  return Verdict::Indeterminate;
}

inline Verdict cuboid_cuboid(const V3& ha, const M3& Ra, const V3& hb, const M3& Rb, const V3& t, LD eta) {
  // A is grown/shrunk by g and B by 2g: unequal amounts keep faces that are exactly coplanar in the
  // input (equal boxes side by side) apart by g, far above round-off, so the edge clipping never has
  // to decide a degenerate coincidence.
  const auto overlaps = [&](LD g) {
    return boxes_intersect({ha[0] + g, ha[1] + g, ha[2] + g}, Ra, {hb[0] + 2 * g, hb[1] + 2 * g, hb[2] + 2 * g},
                           Rb, t);
  };
  if (overlaps(-eta)) return Verdict::Overlap;
  if (!overlaps(eta)) return Verdict::Separated;
  return Verdict::Indeterminate;
}

/// Verdict for a general pair, same conventions as anisodyn::overlap (t = r_b − r_a; columns of
/// Ra, Rb are body axes). eta < 0 selects the default band.
inline Verdict overlap_verdict(const Shape& a, const Mat3& Ra, const Shape& b, const Mat3& Rb, const Vec3& t,
                               double eta = -1.0) {
  const LD e = eta >= 0 ? LD(eta) : LD(kBandRelative) * (LD(a.inscribed_radius()) + LD(b.inscribed_radius()));
  const V3 tl = ld(t);
  const auto K = [](ShapeKind x, ShapeKind y) { return 3 * static_cast<int>(x) + static_cast<int>(y); };
  using S = ShapeKind;
  switch (K(a.kind, b.kind)) {
    case K(S::Sphere, S::Sphere):
      return sphere_sphere(LD(a.diameter) / 2, LD(b.diameter) / 2, tl, e);
    case K(S::Cuboid, S::Sphere):
      return cuboid_sphere(ld(a.half_extents()), ld(Ra), LD(b.diameter) / 2, tl, e);
    case K(S::Sphere, S::Cuboid):
      return cuboid_sphere(ld(b.half_extents()), ld(Rb), LD(a.diameter) / 2, scale(-1, tl), e);
    case K(S::Cuboid, S::Cuboid):
      return cuboid_cuboid(ld(a.half_extents()), ld(Ra), ld(b.half_extents()), ld(Rb), tl, e);
    case K(S::Spherocylinder, S::Spherocylinder): {
      const LD d2 = segment_segment_dist2(column(ld(Ra), 2), LD(a.length) / 2, column(ld(Rb), 2),
                                          LD(b.length) / 2, tl);
      return verdict_from_distance(d2, LD(a.diameter) / 2 + LD(b.diameter) / 2, e);
    }
    case K(S::Spherocylinder, S::Sphere):
      return verdict_from_distance(point_segment_dist2(column(ld(Ra), 2), LD(a.length) / 2, tl),
                                   LD(a.diameter) / 2 + LD(b.diameter) / 2, e);
    case K(S::Sphere, S::Spherocylinder):
      return verdict_from_distance(point_segment_dist2(column(ld(Rb), 2), LD(b.length) / 2, scale(-1, tl)),
                                   LD(a.diameter) / 2 + LD(b.diameter) / 2, e);
    default: break;
  }
  throw std::invalid_argument("reference: unsupported shape pair");
}

}  // namespace anisodyn::reference

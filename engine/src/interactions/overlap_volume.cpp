#include "anisodyn/interactions/overlap_volume.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace anisodyn {

namespace {

constexpr int kGaussNodes = 256;       // on t ∈ [0, π/2]; converged to round-off for x ≥ 10⁻⁶
constexpr int kCoarseIntervals = 4096;  // x ∈ [0, 1]
constexpr int kFineIntervals = 4096;    // x ∈ [0, 1/64]: f has an x² ln x term at x = 0
constexpr double kFineEnd = 1.0 / 64.0;  // a knot of both grids, so the interpolant stays C¹

struct GaussLegendre {
  std::array<double, kGaussNodes> weight{};    // for nodes on [−1, 1]
  std::array<double, kGaussNodes> cos{}, sin{};  // of the nodes mapped to t ∈ [0, π/2]
};

// Nodes by Newton's method on P_n from the Chebyshev-like first guess, weights 2/((1 − z²)P_n′²).
const GaussLegendre& gauss_legendre() {
  static const GaussLegendre rule = [] {
    GaussLegendre g;
    const int n = kGaussNodes;
    for (int i = 0; i < n; ++i) {
      double z = std::cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 1.0;
      for (int iteration = 0; iteration < 100; ++iteration) {
        double p0 = 1.0, p1 = 0.0;
        for (int j = 1; j <= n; ++j) {
          const double p2 = p1;
          p1 = p0;
          p0 = ((2.0 * j - 1.0) * z * p1 - (j - 1.0) * p2) / j;
        }
        dp = n * (z * p0 - p1) / (z * z - 1.0);
        const double step = p0 / dp;
        z -= step;
        if (std::abs(step) < 1e-16) break;
      }
      const auto k = static_cast<std::size_t>(i);
      g.weight[k] = 2.0 / ((1.0 - z * z) * dp * dp);
      g.cos[k] = std::cos(0.25 * M_PI * (z + 1.0));
      g.sin[k] = std::sin(0.25 * M_PI * (z + 1.0));
    }
    return g;
  }();
  return rule;
}

// Cubic Hermite interpolant of (F, F′) on n equal intervals of [0, end].
struct HermiteTable {
  double end = 1.0;
  int n = 0;
  std::vector<double> value, slope;

  HermiteTable(double end_, int n_) : end(end_), n(n_), value(static_cast<std::size_t>(n_) + 1), slope(value.size()) {
    for (int i = 0; i <= n; ++i) {
      const OverlapIntegral q = overlap_integral(end * i / n);
      value[static_cast<std::size_t>(i)] = q.f;
      slope[static_cast<std::size_t>(i)] = q.f_prime;
    }
    slope[0] = 0.0;  // exact; the quadrature leaves ~10⁻¹³ from the cancellation in −4hI + 2h²J
  }
  // Interpolant at x ∈ [0, end] and, in *derivative, its exact derivative.
  double operator()(double x, double* derivative) const {
    const double y = x / end * n;
    const int i = std::min(static_cast<int>(y), n - 1);
    const double t = y - i, h = end / n, u = 1.0 - t;
    const auto k = static_cast<std::size_t>(i);
    const double f0 = value[k], f1 = value[k + 1], m0 = h * slope[k], m1 = h * slope[k + 1];
    if (derivative) *derivative = (6.0 * t * u * (f1 - f0) + u * (u - 2.0 * t) * m0 + t * (t - 2.0 * u) * m1) / h;
    return (1.0 + 2.0 * t) * u * u * f0 + t * u * u * m0 + t * t * (3.0 - 2.0 * t) * f1 - t * t * u * m1;
  }
};

// f(xD)/D³ from the two-level table; *derivative = d/dx of it (= f′/D²). x ≥ 0.
double f_scaled(double x, double* derivative) {
  static const HermiteTable coarse(1.0, kCoarseIntervals), fine(kFineEnd, kFineIntervals);
  if (x >= 1.0) {
    if (derivative) *derivative = 0.0;
    return 0.0;
  }
  return x < kFineEnd ? fine(x, derivative) : coarse(x, derivative);
}

// Lens area A_ov(d) of two discs of diameter D at centre distance 0 ≤ d < D, and *slope = A′ = −√(D² − d²).
// With the full opening angle φ = 2 arccos(d/D), A = (D²/4)(φ − sin φ), the same as
// (D²/2) arccos(d/D) − (d/2)√(D² − d²) but without its cancellation as d → D (A ~ (D − d)^{3/2}):
// φ comes from atan2, and φ − sin φ is summed as its series for small φ.
double lens_area(double d, double D, double* slope) {
  const double root = std::sqrt((D - d) * (D + d));
  *slope = -root;
  const double phi = 2.0 * std::atan2(root, d);
  double phi_minus_sin = 0.0;
  if (phi > 0.25) {
    phi_minus_sin = phi - std::sin(phi);
  } else {
    const double phi2 = phi * phi;
    double term = phi * phi2 / 6.0;  // φ³/3! − φ⁵/5! + … − φ¹⁷/17!: truncation < 10⁻²⁴ relative
    for (int n = 3; n <= 17; n += 2) {
      phi_minus_sin += term;
      term *= -phi2 / ((n + 1.0) * (n + 2.0));
    }
  }
  return 0.25 * D * D * phi_minus_sin;
}

// sign with sign(0) = 0: the symmetric subgradient of |x| at the kink.
double sign_of(double x) { return static_cast<double>((x > 0.0) - (x < 0.0)); }

}  // namespace

// With D = 1, h = (1 − x)/2, H = (1 + x)/2 and p = h sin t, the integrand of f becomes
// h cos t √(H² − h² sin²t) = h cos t √(x + h² cos²t), so that
//   f = 4h² I,  I = ∫_{−π/2}^{π/2} cos²t √(x + h² cos²t) dt,
//   f′ = −4h I + 2h² J,  J = ∫_{−π/2}^{π/2} cos²t (H + h sin²t) / √(x + h² cos²t) dt
// (differentiating under the integral with dh/dx = −½, dH/dx = ½). Both integrands are even in t and
// smooth for x > 0 (a kink of width ~√x forms at t = π/2 as x → 0); at x = 1 (h = 0) f = f′ = 0, at
// x = 0 f = 16h³/3 = 2/3 and f′ = 0.
OverlapIntegral overlap_integral(double x) {
  if (!(x >= 0.0 && x <= 1.0)) throw std::invalid_argument("overlap_integral: x = d/D must lie in [0, 1]");
  const GaussLegendre& g = gauss_legendre();
  const double h = 0.5 * (1.0 - x), H = 0.5 * (1.0 + x);
  double I = 0.0, J = 0.0;
  for (int i = 0; i < kGaussNodes; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double c = g.cos[k], s = g.sin[k];
    const double root = std::sqrt(x + h * h * c * c);
    I += g.weight[k] * c * c * root;
    J += g.weight[k] * c * c * (H + h * s * s) / root;
  }
  I *= 0.5 * M_PI;  // 2 (even integrand) × π/4 (Jacobian)
  J *= 0.5 * M_PI;
  return {4.0 * h * h * I, -4.0 * h * I + 2.0 * h * h * J};
}

OverlapVolume::OverlapVolume(const OverlapVolumeSettings& settings) : s_(settings) {
  if (!(std::isfinite(s_.length) && std::isfinite(s_.diameter) && std::isfinite(s_.hardness)))
    throw std::invalid_argument("OverlapVolume: length, diameter and hardness must be finite");
  if (!(s_.diameter > 0.0)) throw std::invalid_argument("OverlapVolume: the diameter must be positive");
  if (!(s_.length > s_.diameter)) throw std::invalid_argument("OverlapVolume: the length must exceed the diameter");
  if (!(s_.hardness >= 0.0)) throw std::invalid_argument("OverlapVolume: the hardness must not be negative");
}

double OverlapVolume::f(double d) const {
  const double D = s_.diameter;
  return D * D * D * f_scaled(d / D, nullptr);
}

double OverlapVolume::f_prime(double d) const {
  const double D = s_.diameter;
  double slope = 0.0;
  f_scaled(d / D, &slope);
  return D * D * slope;
}

// Segment reach of the near-parallel branch. Take σ = sign(û_i·û_j) and γ′ ∈ [0, π/2] the angle of û_i
// and σû_j, so sin γ′ = sin γ < D/L, i.e. γ′ < γ_s; m = |û_i + σû_j| = 2 cos(γ′/2), ū = (û_i + σû_j)/m,
// and r_ij = q + a ū with q ⊥ ū, |q| = d and a = r_ij·ū = (r_ij·û_i + σ r_ij·û_j)/m. A pair interacts
// only if d < D and L_ov > 0, i.e. |r_ij·û_i| + |r_ij·û_j| < 2L, so |a| < 2L/m. The points of
// parameter t on rod i and −t on rod j (along σû_j) are r_ij + t m ū = q + (a + t m) ū apart. With
// t = −a/m clamped to [−L/2, L/2] the gap along ū is 0 if |a| ≤ mL/2 and otherwise
// |a| − mL/2 < 2L/m − mL/2 = L sin²(γ′/2)/cos(γ′/2) < ε (it grows with γ′). So the segment distance
// is below √(d² + ε²) < √(D² + ε²). Main-branch pairs interact only at segment distance below D: the
// segment-distance rule uses it, and the interior-only rule's line distance equals it when both
// closest points lie on the segments.
double OverlapVolume::segment_cutoff() const {
  const double L = s_.length, D = s_.diameter;
  const double half = 0.5 * std::asin(D / L), sin_half = std::sin(half);
  return std::hypot(D, L * sin_half * sin_half / std::cos(half));
}

double OverlapVolume::hardness_for(double diameter, double kT) {
  if (!(diameter > 0.0)) throw std::invalid_argument("OverlapVolume::hardness_for: the diameter must be positive");
  return kT / (diameter * diameter * diameter * f_scaled(0.8, nullptr));
}

RodPairTerm OverlapVolume::operator()(const Vec3& r_ji, const Vec3& u_i, const Vec3& u_j) const {
  RodPairTerm term;
  const double L = s_.length, D = s_.diameter, k = s_.hardness;
  if (r_ji.squaredNorm() >= cutoff() * cutoff()) return term;
  // The main branch works on the pair in a fixed order, lexicographically smaller axis first, so that
  // the calls for i and for j do the same arithmetic: the same branch and energy, and F_j = −F_i
  // exactly. The near-parallel branch is symmetric as written.
  const bool swapped = std::lexicographical_compare(u_j.data(), u_j.data() + 3, u_i.data(), u_i.data() + 3);
  const Vec3& u1 = swapped ? u_j : u_i;
  const Vec3& u2 = swapped ? u_i : u_j;
  const Vec3 normal12 = u1.cross(u2);
  const double sin2 = normal12.squaredNorm(), sin_g = std::sqrt(sin2), c = u1.dot(u2);

  if (sin_g >= D / L) {
    // Closest points p_1 = r_1 + a û_1, p_2 = r_2 + b û_2 minimise |w|², w = p_1 − p_2 = a û_1 − b û_2 − t,
    // t = r_2 − r_1.
    const Vec3 t = swapped ? Vec3(-r_ji) : r_ji;
    // Most listed pairs of long rods do not touch: the distance of the infinite axes, a lower bound
    // of the segments' distance, rejects them before the closest points are sought.
    const double line_gap = std::abs(t.dot(normal12)) / sin_g;
    if (line_gap >= D) {
      term.distance = line_gap;
      return term;
    }
    const double half = 0.5 * L, t1 = t.dot(u1), t2 = t.dot(u2);
    double a = (t1 - c * t2) / sin2, b = 0.0;  // a of the infinite lines
    if (s_.rule == FiniteLengthRule::SegmentDistance) {
      // Convex quadratic on the square |a|, |b| ≤ L/2: clamp the strip minimiser a, take the best b
      // for it, and if b had to be clamped, the best a on that edge.
      a = std::clamp(a, -half, half);
      b = std::clamp(c * a - t2, -half, half);
      a = std::clamp(t1 + c * b, -half, half);
    } else {
      b = (c * t1 - t2) / sin2;
    }
    const Vec3 w12 = a * u1 - b * u2 - t;
    const double d = w12.norm();
    term.distance = d;
    const bool inside = s_.rule == FiniteLengthRule::SegmentDistance || (std::abs(a) <= half && std::abs(b) <= half);
    if (!inside || d >= D) return term;
    double fp = 0.0;
    const double fd = D * D * D * f_scaled(d / D, &fp);
    fp *= D * D;
    term.interacts = fd > 0.0;
    term.energy = k * fd / sin_g;
    // Back to rod i: p_i − p_j, the parameter of p_i on rod i, and û_i × û_j.
    const Vec3 w = swapped ? Vec3(-w12) : w12;
    const double a_i = swapped ? b : a;
    const Vec3 normal = swapped ? Vec3(-normal12) : normal12;
    // Envelope theorem: ∇_{r_i} d = ŵ and ∂d/∂û_i = a_i ŵ, at fixed (clamped) parameters.
    if (d > 0.0) term.force = (-k * fp / (sin_g * d)) * w;
    // ∂(1/sin γ)/∂û_i = (c/sin³γ) û_j, so −û_i × k f ∂(1/sin γ)/∂û_i = −k f c (û_i × û_j)/sin³γ.
    term.torque = a_i * u_i.cross(term.force) - (k * fd * c / (sin2 * sin_g)) * normal;
    return term;
  }

  // Near-parallel branch.
  term.near_parallel = true;
  const Vec3 r = -r_ji;  // r_ij
  const double sigma = c >= 0.0 ? 1.0 : -1.0;
  const Vec3 m = u_i + sigma * u_j;
  const double m_norm = m.norm();
  const Vec3 axis = m / m_norm;
  const double along = r.dot(axis);
  const Vec3 q = r - along * axis;  // perpendicular separation, from j to i
  const double d = q.norm();
  term.distance = d;
  const double ri = r.dot(u_i), rj = r.dot(u_j);
  const double overlap_length = L - 0.5 * (std::abs(ri) + std::abs(rj));
  if (overlap_length <= 0.0 || d >= D) return term;
  double area_prime = 0.0;
  const double area = lens_area(d, D, &area_prime);
  term.interacts = area > 0.0;
  term.energy = k * area * overlap_length;
  // ∇_{r_i} d = q̂; ∇_{r_i} L_ov = −½[sgn(r_ij·û_i) û_i + sgn(r_ij·û_j) û_j]. At d = 0 (tip of the cone
  // A_ov(|q|)) the symmetric subgradient 0 is used for the d-part.
  const Vec3 q_hat = d > 0.0 ? Vec3(q / d) : Vec3::Zero();
  const double si = sign_of(ri), sj = sign_of(rj);
  term.force = -k * (area_prime * overlap_length * q_hat - 0.5 * area * (si * u_i + sj * u_j));
  // ∂d/∂û_i = −(r_ij·ū)/|û_i + σû_j| q̂ (ū depends on û_i), ∂L_ov/∂û_i = −½ sgn(r_ij·û_i) r_ij, so
  // T_i = −û_i × ∂Φ/∂û_i = k A′ L_ov (r_ij·ū)/|û_i + σû_j| (û_i × q̂) + ½ k A sgn(r_ij·û_i) (û_i × r_ij).
  term.torque = (k * area_prime * overlap_length * along / m_norm) * u_i.cross(q_hat) +
                (0.5 * k * area * si) * u_i.cross(r);
  return term;
}

BranchSwitchJump measure_branch_switch_jump(const OverlapVolume& ov, double d_max, double offset_max, int steps) {
  const OverlapVolumeSettings& s = ov.settings();
  const double switch_sin = s.diameter / s.length;
  const double below = std::asin(switch_sin * (1.0 - 1e-9)), above = std::asin(switch_sin * (1.0 + 1e-9));
  const Vec3 u_i = Vec3::UnitX();
  BranchSwitchJump out;
  const int n = std::max(steps, 1);
  for (int id = 0; id <= n; ++id) {
    for (int io = 0; io <= n; ++io) {
      const double d = d_max * id / n, offset = offset_max * io / n;
      const Vec3 r_ji(offset, 0.0, d);
      const RodPairTerm lo = ov(r_ji, u_i, Vec3(std::cos(below), std::sin(below), 0.0));
      const RodPairTerm hi = ov(r_ji, u_i, Vec3(std::cos(above), std::sin(above), 0.0));
      if (id == 0 && io == 0 && hi.energy > 0.0) out.contact_energy_ratio = lo.energy / hi.energy;
      if (!lo.interacts && !hi.interacts) continue;
      const double de = std::abs(lo.energy - hi.energy), e = std::max(lo.energy, hi.energy);
      const double flo = lo.force.norm(), fhi = hi.force.norm();
      const double df = std::abs(flo - fhi), fmax = std::max(flo, fhi);
      out.max_energy_jump = std::max(out.max_energy_jump, de);
      out.max_force_jump = std::max(out.max_force_jump, df);
      if (e > 0.0 && de / e > out.max_relative_energy_jump) {
        out.max_relative_energy_jump = de / e;
        out.worst_energy_d = d;
        out.worst_energy_offset = offset;
      }
      if (fmax > 0.0 && df / fmax > out.max_relative_force_jump) {
        out.max_relative_force_jump = df / fmax;
        out.worst_force_d = d;
        out.worst_force_offset = offset;
      }
    }
  }
  return out;
}

}  // namespace anisodyn

// Overlap-volume rod potential (interactions/overlap_volume.hpp; spec 20 §4, spec 70 §5.2; docs/bd.md):
// the f table against the spec's numbers and an independent long-double reference
// (tests/support/reference_overlap_volume.hpp), pair energies against that reference, forces and
// torques against central finite differences of the energy for random pairs of both branches and
// both finite-length rules, Newton's third law, the balance of angular momentum, the segment
// cut-off that neighbour lists use (no pair interacts beyond it; near-parallel pairs do beyond D),
// and the size of the published discontinuity at the branch switch.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "anisodyn/core/rng.hpp"
#include "anisodyn/geometry/spherocylinder.hpp"
#include "anisodyn/interactions/overlap_volume.hpp"
#include "reference_overlap_volume.hpp"

using namespace anisodyn;
namespace ref = anisodyn::reference;

namespace {

constexpr double kD = 14.8, kLong = 880.0, kShort = 5.0 * kD, kT = 1.0;

OverlapVolume make(double length, FiniteLengthRule rule = FiniteLengthRule::SegmentDistance) {
  return OverlapVolume({length, kD, OverlapVolume::hardness_for(kD, kT), rule});
}

Vec3 random_unit(Rng& rng) { return Vec3(rng.normal(), rng.normal(), rng.normal()).normalized(); }

Vec3 random_perpendicular(Rng& rng, const Vec3& u) {
  const Vec3 v = random_unit(rng);
  return (v - v.dot(u) * u).normalized();
}

// û rotated by the angle asin(sin_g) about a random axis perpendicular to it, reversed half the time.
Vec3 tilted(Rng& rng, const Vec3& u, double sin_g) {
  const Vec3 v = (Eigen::AngleAxisd(std::asin(sin_g), random_perpendicular(rng, u)) * u).normalized();
  return rng.uniform() < 0.5 ? v : Vec3(-v);
}

struct Pair {
  Vec3 r_ji, u_i, u_j;
};

// Random pairs, most of them interacting:
//   kind 0: main branch, random axes with sin γ ≥ D/L; the infinite axes pass at distance
//           d₀ ∈ [0, 1.1 D) at line parameters a₀, b₀ ∈ [−0.6 L, 0.6 L] (beyond ±L/2: clamped);
//   kind 1: the same with sin γ ∈ [D/L, 3 D/L] (just above the switch);
//   kind 2: near-parallel, sin γ ∈ [0, D/L) (exactly parallel one time in twenty), centre offset
//           along û_i in [−1.1 L, 1.1 L] and perpendicular to it in [0, 1.1 D).
Pair random_pair(Rng& rng, double L, int kind) {
  const double switch_sin = kD / L;
  Pair p;
  p.u_i = random_unit(rng);
  if (kind == 2) {
    const double sin_g = rng.uniform() < 0.05 ? 0.0 : switch_sin * rng.uniform();
    p.u_j = tilted(rng, p.u_i, sin_g);
    p.r_ji = rng.uniform(-1.1, 1.1) * L * p.u_i + rng.uniform(0.0, 1.1 * kD) * random_perpendicular(rng, p.u_i);
    return p;
  }
  if (kind == 1) {
    p.u_j = tilted(rng, p.u_i, switch_sin * rng.uniform(1.0, 3.0));
  } else {
    do p.u_j = random_unit(rng);
    while (p.u_i.cross(p.u_j).norm() < switch_sin);
  }
  const Vec3 n = p.u_i.cross(p.u_j).normalized();
  const double a0 = rng.uniform(-0.6, 0.6) * L, b0 = rng.uniform(-0.6, 0.6) * L, d0 = rng.uniform(-1.1, 1.1) * kD;
  p.r_ji = a0 * p.u_i - b0 * p.u_j - d0 * n;  // p_i − p_j = d₀ n̂ for the infinite lines
  return p;
}

// What must not change inside a finite-difference stencil: the branch, whether the pair interacts,
// which closest-point parameters are clamped (segment rule) or outside (interior-only rule) by the
// reference, and the signs of r_ij·û_i, r_ij·û_j (near-parallel branch: kinks of |·| in L_ov).
struct Regime {
  bool near_parallel = false, interacts = false;
  int side_a = 0, side_b = 0, sign_i = 0, sign_j = 0;
  bool operator==(const Regime&) const = default;
};

Regime regime_of(const OverlapVolume& ov, const Pair& p) {
  const RodPairTerm t = ov(p.r_ji, p.u_i, p.u_j);
  Regime g;
  g.near_parallel = t.near_parallel;
  g.interacts = t.interacts;
  const double half = 0.5 * ov.settings().length;
  if (t.near_parallel) {
    const double ri = -p.r_ji.dot(p.u_i), rj = -p.r_ji.dot(p.u_j);
    g.sign_i = (ri > 0) - (ri < 0);
    g.sign_j = (rj > 0) - (rj < 0);
  } else {
    const ref::ClosestPoints c = ov.settings().rule == FiniteLengthRule::SegmentDistance
                                     ? ref::segment_closest(p.r_ji, p.u_i, p.u_j, half)
                                     : ref::line_closest(p.r_ji, p.u_i, p.u_j, half);
    g.side_a = c.side_a;
    g.side_b = c.side_b;
  }
  return g;
}

struct FdStats {
  long pairs = 0, interacting = 0, compared = 0, compared_clamped = 0, excluded_regime = 0, excluded_singular = 0;
  double max_force_error = 0.0, max_torque_error = 0.0;
  double max_newton = 0.0, max_angular = 0.0, max_energy_asymmetry = 0.0;
  std::string worst;
};

// Finite differences: five-point central differences (error h⁴ Φ⁽⁵⁾/30) under translations of r_i
// by ±h, ±2h and rotations of û_i by ±ε, ±2ε about each lab axis, with ε L/2 = h so that no point of
// rod i moves further than h. h = 2×10⁻⁵ D balances round-off (Φ up to ~800 kT) against truncation
// (measured: ≤ 3.3×10⁻⁷ away from the singular points below; 10⁻⁵ D gives up to 4×10⁻⁷ of round-off,
// 10⁻⁴ D needs a wider band around the singular points).
constexpr double kStepOverD = 2e-5;
// Forces are compared relative to max(|F|, F_floor), torques to max(|T|, F_floor L/2) (the torque of
// F_floor at a rod end): a force of 0.01 kT/D displaces a rod by 7×10⁻⁶ D per BD step (spec 20 §4.5:
// the cap, 143 kT/D, displaces it by D/10), far below the noise of 0.026 D per step.
constexpr double kForceFloor = 1e-2 * kT / kD;
// Pairs this close (in d) to a point where Φ is not smooth enough for the stencil are not compared:
// d → 0 in both branches (main: f″ diverges like ln d; near-parallel: A_ov(|q|) is a cone about q = 0),
// and d → D in the near-parallel branch (A″ = d/√(D² − d²)). The band is 15 steps; the errors in it
// grow to 10⁻⁵–10⁻³ as d approaches the singular point.
constexpr double kSingularBandOverD = 3e-4;

void check_gradients(const OverlapVolume& ov, Rng& rng, long n_pairs, FdStats (&stats)[2]) {
  const double L = ov.settings().length, h = kStepOverD * kD, eps = 2.0 * h / L;
  const double torque_floor = kForceFloor * 0.5 * L;
  for (long n = 0; n < n_pairs; ++n) {
    const int kind = static_cast<int>(n % 5) < 2 ? 0 : (n % 5 == 2 ? 1 : 2);
    const Pair p = random_pair(rng, L, kind);
    const RodPairTerm t = ov(p.r_ji, p.u_i, p.u_j);
    FdStats& s = stats[t.near_parallel ? 1 : 0];
    ++s.pairs;
    if (!t.interacts) continue;
    ++s.interacting;

    // Newton's third law (exact: both calls do the same arithmetic) and the angular momentum balance
    // T_i + T_j + r_ij × F_i = 0 (to round-off).
    const RodPairTerm tj = ov(-p.r_ji, p.u_j, p.u_i);
    const double fscale = std::max(t.force.norm(), kForceFloor);
    s.max_newton = std::max(s.max_newton, (t.force + tj.force).norm() / fscale);
    const double tscale =
        std::max(t.torque.norm() + tj.torque.norm() + p.r_ji.norm() * t.force.norm(), torque_floor);
    s.max_angular = std::max(s.max_angular, (t.torque + tj.torque - p.r_ji.cross(t.force)).norm() / tscale);
    s.max_energy_asymmetry = std::max(s.max_energy_asymmetry, std::abs(t.energy - tj.energy) / t.energy);

    const Regime g0 = regime_of(ov, p);
    bool same_regime = true;
    Vec3 force_fd, torque_fd;
    for (int axis = 0; axis < 3; ++axis) {
      const Vec3 e = Vec3::Unit(axis);
      double ef[5], et[5];  // at −2, −1, 0, +1, +2 steps
      for (int k = -2; k <= 2; ++k) {
        if (k == 0) continue;
        const Pair moved{p.r_ji - k * h * e, p.u_i, p.u_j};  // r_i → r_i + k h ê
        const Pair turned{p.r_ji, Eigen::AngleAxisd(k * eps, e) * p.u_i, p.u_j};
        ef[k + 2] = ov(moved.r_ji, moved.u_i, moved.u_j).energy;
        et[k + 2] = ov(turned.r_ji, turned.u_i, turned.u_j).energy;
        same_regime = same_regime && regime_of(ov, moved) == g0 && regime_of(ov, turned) == g0;
      }
      // Five-point central difference: error h⁴ Φ⁽⁵⁾/30.
      force_fd[axis] = -(8.0 * (ef[3] - ef[1]) - (ef[4] - ef[0])) / (12.0 * h);
      torque_fd[axis] = -(8.0 * (et[3] - et[1]) - (et[4] - et[0])) / (12.0 * eps);
    }
    if (!same_regime) {
      ++s.excluded_regime;
      continue;
    }
    const double band = kSingularBandOverD * kD;
    if (t.distance < band || (t.near_parallel && kD - t.distance < band)) {
      ++s.excluded_singular;
      continue;
    }
    ++s.compared;
    s.compared_clamped += g0.side_a != 0 || g0.side_b != 0;  // segment rule: clamped closest points
    const double ef = (force_fd - t.force).norm() / fscale;
    const double et = (torque_fd - t.torque).norm() / std::max(t.torque.norm(), torque_floor);
    if (std::max(ef, et) > std::max(s.max_force_error, s.max_torque_error)) {
      char buf[320];
      std::snprintf(buf, sizeof buf, "pair %ld: d/D=%.6f E=%.6g |F|=%.6g |T|=%.6g errF=%.3g errT=%.3g", n,
                    t.distance / kD, t.energy, t.force.norm(), t.torque.norm(), ef, et);
      s.worst = buf;
    }
    s.max_force_error = std::max(s.max_force_error, ef);
    s.max_torque_error = std::max(s.max_torque_error, et);
  }
}

}  // namespace

TEST(OverlapVolume, RejectsNonsensicalSettings) {
  EXPECT_THROW(OverlapVolume({100.0, 0.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(OverlapVolume({100.0, -1.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(OverlapVolume({10.0, 10.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(OverlapVolume({100.0, 10.0, -1.0}), std::invalid_argument);
  EXPECT_THROW(OverlapVolume({NAN, 10.0, 1.0}), std::invalid_argument);
  EXPECT_NO_THROW(OverlapVolume({100.0, 10.0, 0.0}));
}

TEST(OverlapVolume, TableMatchesTheSpecNumbers) {
  const OverlapVolume ov = make(kLong);
  const double D3 = kD * kD * kD;
  EXPECT_NEAR(ov.f(0.0) / D3, 2.0 / 3.0, 1e-12 * 2.0 / 3.0);
  // spec 70 §5.2, printed to six decimals.
  const double x[] = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.99, 1.0};
  const double f[] = {0.634827, 0.567489, 0.481441, 0.386531, 0.290375, 0.199479,
                      0.119696, 0.056461, 0.014917, 0.003829, 0.000156, 0.0};
  for (int i = 0; i < 12; ++i) EXPECT_NEAR(ov.f(x[i] * kD) / D3, f[i], 0.5e-6) << "d/D = " << x[i];
  // Slopes f′/D², printed to four decimals; 0 at both ends.
  EXPECT_NEAR(ov.f_prime(0.2 * kD) / (kD * kD), -0.7862, 0.5e-4);
  EXPECT_NEAR(ov.f_prime(0.5 * kD) / (kD * kD), -0.9455, 0.5e-4);
  EXPECT_NEAR(ov.f_prime(0.8 * kD) / (kD * kD), -0.5323, 0.5e-4);
  EXPECT_EQ(ov.f_prime(0.0), 0.0);
  EXPECT_EQ(ov.f_prime(kD), 0.0);
  EXPECT_EQ(ov.f(1.5 * kD), 0.0);
  // Hardness (spec 70 §5.2): k D³ = 17.7113 kT; k f(0), k f(0.5 D), k f(0.9 D) in kT.
  const double k = OverlapVolume::hardness_for(kD, kT);
  EXPECT_NEAR(k * ov.f(0.8 * kD), kT, 1e-14);
  EXPECT_NEAR(k * D3, 17.7113, 0.5e-4);
  EXPECT_NEAR(k * ov.f(0.0), 11.8075, 0.5e-4);
  EXPECT_NEAR(k * ov.f(0.5 * kD), 5.1429, 0.5e-4);
  EXPECT_NEAR(k * ov.f(0.9 * kD), 0.2642, 0.5e-4);
}

TEST(OverlapVolume, TableMatchesTheIndependentReference) {
  // The reference checks itself: f(0) = 2/3 exactly, and halving its step changes nothing.
  EXPECT_NEAR(static_cast<double>(ref::overlap_f(0.0L)), 2.0 / 3.0, 1e-17);
  for (const long double x : {1e-6L, 0.3L, 0.97L})
    EXPECT_NEAR(static_cast<double>((ref::overlap_f(x, 1.0L / 128) - ref::overlap_f(x)) / ref::overlap_f(x)), 0.0, 1e-17);

  const OverlapVolume ov = make(kLong);
  const double D3 = kD * kD * kD, D2 = kD * kD;
  double worst_f = 0.0, worst_x = 0.0, worst_quadrature = 0.0;
  double worst_fp_near0 = 0.0, worst_fp = 0.0, worst_fp_quadrature = 0.0;  // |Δf′|/D²: x < 10⁻⁴, x ≥ 10⁻⁴
  int points = 0;
  for (int i = 0; i < 1000; ++i) {
    // 200 logarithmically spaced points in [10⁻⁸, 10⁻²] (f has an x² ln x term at x = 0), then 800
    // uniform ones up to x = 0.999, off the knots.
    const double x = i < 200 ? std::pow(10.0, -8.0 + 6.0 * i / 199.0) : 0.01 + 0.989 * (i - 199.5) / 800.0;
    const long double f_ref = ref::overlap_f(x), fp_ref = ref::overlap_f_prime(x);
    const long double fq_ref = x < 1e-6 ? ref::overlap_f(1e-6L) : f_ref, fpq_ref = x < 1e-6 ? ref::overlap_f_prime(1e-6L) : fp_ref;
    const double ef = std::abs(static_cast<double>((ov.f(x * kD) / D3 - f_ref) / f_ref));
    if (ef > worst_f) worst_x = x;
    worst_f = std::max(worst_f, ef);
    const double efp = std::abs(static_cast<double>(ov.f_prime(x * kD) / D2 - fp_ref));
    (x < 1e-4 ? worst_fp_near0 : worst_fp) = std::max(x < 1e-4 ? worst_fp_near0 : worst_fp, efp);
    const OverlapIntegral q = overlap_integral(std::max(x, 1e-6));  // its documented range (and the table's nodes)
    worst_quadrature = std::max(worst_quadrature, std::abs(static_cast<double>((q.f - fq_ref) / fq_ref)));
    worst_fp_quadrature = std::max(worst_fp_quadrature, std::abs(static_cast<double>(q.f_prime - fpq_ref)));
    ++points;
  }
  std::printf("f table vs reference at %d points: max rel %.3g (x = %.6g); interpolant f' max |error|/D^2 %.3g "
              "(x >= 1e-4), %.3g (x < 1e-4); quadrature alone: f max rel %.3g, f' max |error|/D^2 %.3g\n",
              points, worst_f, worst_x, worst_fp, worst_fp_near0, worst_quadrature, worst_fp_quadrature);
  EXPECT_LT(worst_f, 1e-10);
  EXPECT_LT(worst_quadrature, 1e-14);
  EXPECT_LT(worst_fp_quadrature, 1e-14);
  // f′ of the interpolant: f″ diverges like 2 ln(1/x) at x = 0, which the first cubic cannot follow.
  EXPECT_LT(worst_fp, 2e-9);
  EXPECT_LT(worst_fp_near0, 1e-6);
}

TEST(OverlapVolume, PerpendicularCrossingAndFullParallelOverlap) {
  for (const double L : {kLong, kShort}) {
    const OverlapVolume ov = make(L);
    const double k = ov.settings().hardness;
    // Perpendicular rods crossing at their centres: the Steinmetz volume (2/3) D³.
    const RodPairTerm cross = ov(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY());
    EXPECT_TRUE(cross.interacts);
    EXPECT_FALSE(cross.near_parallel);
    EXPECT_NEAR(cross.energy / k, 2.0 / 3.0 * kD * kD * kD, 1e-12 * kD * kD * kD);
    EXPECT_EQ(cross.force.norm(), 0.0);
    EXPECT_EQ(cross.torque.norm(), 0.0);
    // Coincident parallel rods: (π/4) D² L (827.1 kT for L/D = 59.46, spec 70 §5.2).
    const RodPairTerm full = ov(Vec3::Zero(), Vec3::UnitZ(), -Vec3::UnitZ());
    EXPECT_TRUE(full.near_parallel);
    EXPECT_NEAR(full.energy / k, M_PI / 4.0 * kD * kD * L, 1e-12 * kD * kD * L);
    if (L == kLong) {
      EXPECT_NEAR(full.energy, 827.1, 0.05);
    }
    // Beyond the cut-off nothing interacts; just inside it, rods touching end to end do not either.
    EXPECT_FALSE(ov(Vec3(0.0, 0.0, ov.cutoff()), Vec3::UnitZ(), Vec3::UnitZ()).interacts);
    EXPECT_FALSE(ov(Vec3(0.0, 0.0, L + 0.5 * kD), Vec3::UnitZ(), Vec3::UnitX()).interacts);
  }
}

TEST(OverlapVolume, EnergiesMatchTheReference) {
  Rng rng(20050624, 1);
  for (const double L : {kLong, kShort}) {
    for (const FiniteLengthRule rule : {FiniteLengthRule::SegmentDistance, FiniteLengthRule::InteriorOnly}) {
      const OverlapVolume ov = make(L, rule);
      const double k = ov.settings().hardness;
      double worst = 0.0;
      int interacting = 0;
      for (int n = 0; n < 4000; ++n) {
        const Pair p = random_pair(rng, L, n % 3);
        const double sin_g = p.u_i.cross(p.u_j).norm();
        if (std::abs(sin_g - kD / L) < 1e-12) continue;  // the branch decided by rounding
        const RodPairTerm t = ov(p.r_ji, p.u_i, p.u_j);
        const double e_ref = static_cast<double>(k * ref::overlap_volume(ov.settings(), p.r_ji, p.u_i, p.u_j));
        interacting += t.interacts;
        EXPECT_EQ(t.interacts, e_ref > 0.0) << "pair " << n;
        // 10⁻⁹ kT: well below anything that matters, above the table's error at d → D.
        const double err = std::abs(t.energy - e_ref) / std::max(e_ref, 1e-9 * kT);
        worst = std::max(worst, err);
      }
      std::printf("L/D = %.2f, rule %d: energies vs reference, %d interacting of 4000, max rel error %.3g\n", L / kD,
                  static_cast<int>(rule), interacting, worst);
      EXPECT_LT(worst, 1e-10);
      EXPECT_GT(interacting, 1000);
    }
  }
}

TEST(OverlapVolume, ForcesAndTorquesAreExactGradientsOfTheEnergy) {
  Rng rng(20050624, 2);
  for (const double L : {kLong, kShort}) {
    for (const FiniteLengthRule rule : {FiniteLengthRule::SegmentDistance, FiniteLengthRule::InteriorOnly}) {
      const OverlapVolume ov = make(L, rule);
      FdStats stats[2];
      check_gradients(ov, rng, 100000, stats);
      for (int b = 0; b < 2; ++b) {
        const FdStats& s = stats[b];
        std::printf("L/D = %.2f, rule %s, %s branch: %ld pairs, %ld interacting, %ld compared (%ld with clamped closest points), excluded %ld "
                    "(regime change in the stencil) + %ld (within %.0e D of a singular d); max rel error F %.3g, "
                    "T %.3g; Newton %.3g, angular momentum %.3g, energy asymmetry %.3g\n  worst: %s\n",
                    L / kD, rule == FiniteLengthRule::SegmentDistance ? "segment" : "interior", b ? "near-parallel" : "main",
                    s.pairs, s.interacting, s.compared, s.compared_clamped, s.excluded_regime, s.excluded_singular, kSingularBandOverD,
                    s.max_force_error, s.max_torque_error, s.max_newton, s.max_angular, s.max_energy_asymmetry,
                    s.worst.c_str());
        EXPECT_GT(s.compared, 10000);
        if (b == 0 && rule == FiniteLengthRule::SegmentDistance) {
          EXPECT_GT(s.compared_clamped, 5000);
        }
        EXPECT_LT(s.max_force_error, 1e-6);
        EXPECT_LT(s.max_torque_error, 1e-6);
        EXPECT_EQ(s.max_newton, 0.0);
        EXPECT_EQ(s.max_energy_asymmetry, 0.0);
        EXPECT_LT(s.max_angular, 1e-9);
      }
    }
  }
}

TEST(OverlapVolume, BranchSwitchJumpIsThePublishedOne) {
  const OverlapVolume ov = make(kLong);  // L/D = 59.46
  const BranchSwitchJump at_contact = measure_branch_switch_jump(ov, 0.0, 0.0, 1);
  EXPECT_NEAR(at_contact.contact_energy_ratio, (M_PI / 4.0) / (2.0 / 3.0), 1e-3);
  for (const double L : {kLong, kShort}) {
    const OverlapVolume o = make(L);
    const double k = o.settings().hardness;
    const BranchSwitchJump centred = measure_branch_switch_jump(o, 0.99 * kD, 0.0, 99);
    const BranchSwitchJump all = measure_branch_switch_jump(o, 0.99 * kD, 0.99 * L, 99);
    std::printf("L/D = %.2f: contact ratio %.6f; centred crossing (d <= 0.99 D): max rel jump E %.4f (d/D = %.2f), "
                "|F| %.4f (d/D = %.2f), max jump E %.4g kT, |F| %.4g kT/D\n",
                L / kD, centred.contact_energy_ratio, centred.max_relative_energy_jump, centred.worst_energy_d / kD,
                centred.max_relative_force_jump, centred.worst_force_d / kD, centred.max_energy_jump,
                centred.max_force_jump * kD);
    std::printf("  offsets up to 0.99 L: max rel jump E %.4f (d/D = %.2f, offset/L = %.2f), |F| %.4f (d/D = %.2f, "
                "offset/L = %.2f), max jump E %.4g kT, |F| %.4g kT/D\n",
                all.max_relative_energy_jump, all.worst_energy_d / kD, all.worst_energy_offset / L,
                all.max_relative_force_jump, all.worst_force_d / kD, all.worst_force_offset / L, all.max_energy_jump,
                all.max_force_jump * kD);
    EXPECT_NEAR(centred.contact_energy_ratio, (M_PI / 4.0) / (2.0 / 3.0), 1e-3);
    EXPECT_GT(centred.max_energy_jump, 0.1 * k * kD * kD * L);  // the jump is real and large
  }
}

TEST(OverlapVolume, NoPairInteractsBeyondTheSegmentCutoff) {
  // Random pairs of all kinds, and near-parallel pairs at the edge of the branch's reach: axes in
  // the xy-plane at ±γ/2 to x̂ with sin γ just below D/L, centres A ≈ L/cos(γ/2) apart along x̂
  // (L_ov just above 0) and d ≈ D apart along ẑ, where the segments are √(d² + (A − L cos(γ/2))²) apart.
  Rng rng(20050624, 4);
  for (const double L : {kLong, kShort}) {
    const OverlapVolume ov = make(L);
    const double cutoff = ov.segment_cutoff();
    double widest = 0.0;  // largest segment distance of an interacting pair, over D
    int beyond_d = 0;
    for (int n = 0; n < 40000; ++n) {
      Pair p;
      if (n % 2 == 0) {
        p = random_pair(rng, L, n % 3);
      } else {
        // The excess of the reach over D is ε²/2D, 9×10⁻⁶ D for L/D = 59.46: d and A stay that close.
        const double g = std::asin(kD / L * (1.0 - rng.uniform(1e-9, 1e-4))), c = std::cos(0.5 * g);
        p.u_i = Vec3(c, std::sin(0.5 * g), 0.0);
        p.u_j = Vec3(c, -std::sin(0.5 * g), 0.0);
        p.r_ji = -Vec3(L / c * (1.0 - rng.uniform(1e-9, 1e-6)), 0.0, kD - rng.uniform(0.0, 1.0) * (cutoff - kD));
      }
      const RodPairTerm t = ov(p.r_ji, p.u_i, p.u_j);
      if (!t.interacts) continue;
      const double d = std::sqrt(segment_segment_dist2(p.u_i, 0.5 * L, p.u_j, 0.5 * L, p.r_ji));
      ASSERT_LT(d, cutoff) << "pair " << n;
      widest = std::max(widest, d / kD);
      beyond_d += d > kD;
    }
    std::printf("L/D = %.2f: segment cut-off %.9f D; interacting pairs up to %.9f D apart, %d beyond D\n", L / kD, cutoff / kD,
                widest, beyond_d);
    EXPECT_GT(beyond_d, 1000);                     // a cut-off of D would miss pairs
    EXPECT_GT(widest, 1.0 + 0.9 * (cutoff / kD - 1.0));  // and the bound is nearly reached
  }
}

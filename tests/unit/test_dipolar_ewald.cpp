// Dipolar Ewald sum (spec 10 §6) against an independent brute-force lattice sum, bare pair
// formulas and its own full recomputation.
//
// Energy scale. Unless stated otherwise, "accuracy ε" and "relative" mean relative to N·γ/2: the
// error of βU per dipole in units of γ/2 (the |βu| of a side-by-side contact pair). This is the
// scale the parameter choice controls (docs/ewald.md). A random fluid's βU is a sum of terms of
// both signs and can be much smaller than N·γ/2, so |U| itself is not a usable scale.
//
// Brute-force reference (BruteForce below, long double, written without any Ewald ingredient):
//   U_vac = (γ/2) ½ Σ_n w(|nL|/R) Σ_{i,j}' φ(r_j − r_i + nL),  φ(x) = (1 − 3(Ê·x̂)²)/|x|³,
// i.e. growing spheres of whole image boxes, with a smooth spherical convergence factor w (w = 1
// for |nL| ≤ 0.2R, C^∞ decay to 0 at R). A sharp cut (w = step) converges to the same limit but
// only as ~R⁻³ and with lattice noise; the smooth factor keeps the macroscopic shape spherical, so
// the limit is the vacuum (ε' = 1) spherical result, and converges to ~1e-10 by R ≈ 30 boxes.
// Tinfoil differs from it by the de Leeuw–Perram–Smith surface term:
//   U_tinfoil = U_vac − (γ/2) (2π/(3V)) |M|²,  M = Σ_i Ê = N Ê.
// The relation is checked on its own (one dipole per box) and through every comparison below.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "anisodyn/core/error.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/interactions/dipolar_ewald.hpp"
#include "anisodyn/interactions/dipolar_pair.hpp"
#include "input_error.hpp"

using namespace anisodyn;
using anisodyn::testing_support::input_error;

namespace {

using ld = long double;
constexpr ld kPiL = 3.141592653589793238462643383279502884L;
constexpr double kGamma = 13.0;

/// Random positions in [0, L) with all minimum-image distances ≥ dmin (hard cubes).
Particles random_configuration(const Vec3& L, std::size_t n, std::uint64_t seed, double dmin = 1.0) {
  Rng rng(seed, 17);
  Particles p;
  while (p.size() < n) {
    const Vec3 r(rng.uniform(0, L.x()), rng.uniform(0, L.y()), rng.uniform(0, L.z()));
    bool ok = true;
    for (std::size_t j = 0; j < p.size() && ok; ++j) {
      Vec3 d = r - p.position(j);
      for (int a = 0; a < 3; ++a) d[a] -= L[a] * std::round(d[a] / L[a]);
      ok = d.squaredNorm() >= dmin * dmin;
    }
    if (ok) p.add(0, r, Quat::Identity(), static_cast<std::int64_t>(p.size()));
  }
  return p;
}

/// Direct lattice sum in long double, independent of the Ewald code (see the file comment).
class BruteForce {
 public:
  BruteForce(const Vec3& L, const Vec3& E, double r_max_boxes) : L_(L), E_(E.normalized()) {
    const ld rmax = r_max_boxes * L.minCoeff();
    rmax_ = rmax;
    const int mx = static_cast<int>(std::ceil(rmax / L.x())), my = static_cast<int>(std::ceil(rmax / L.y())),
              mz = static_cast<int>(std::ceil(rmax / L.z()));
    for (int a = -mx; a <= mx; ++a)
      for (int b = -my; b <= my; ++b)
        for (int c = -mz; c <= mz; ++c) {
          const ld x = a * (ld)L.x(), y = b * (ld)L.y(), z = c * (ld)L.z();
          const ld r = std::sqrt(x * x + y * y + z * z);
          if (r > rmax) continue;
          cells_.push_back({r, a, b, c});
        }
  }

  static ld taper(ld t) {  // 1 up to 0.2, C^∞ step down to 0 at 1
    const ld t0 = 0.2L;
    if (t <= t0) return 1;
    if (t >= 1) return 0;
    const ld u = (t - t0) / (1 - t0), a = std::exp(-1 / u), b = std::exp(-1 / (1 - u));
    return b / (a + b);
  }

  ld phi(ld x, ld y, ld z) const {
    const ld s = x * x + y * y + z * z, e = E_.x() * x + E_.y() * y + E_.z() * z;
    return (1 - 3 * e * e / s) / (s * std::sqrt(s));
  }

  /// Per-box sums F(n) = Σ_{i,j}' φ(r_j − r_i + nL) for the dipoles of p (mask), once.
  void load(const Particles& p, const std::vector<char>& mask) {
    x_.clear();
    y_.clear();
    z_.clear();
    for (std::size_t i = 0; i < p.size(); ++i)
      if (mask[i]) {
        x_.push_back(p.x[i]);
        y_.push_back(p.y[i]);
        z_.push_back(p.z[i]);
      }
    const std::size_t n = x_.size();
    F_.assign(cells_.size(), 0);
    for (std::size_t q = 0; q < cells_.size(); ++q) {
      const Cell& c = cells_[q];
      // F(n) = F(−n): compute one half and mirror
      if (c.a < 0 || (c.a == 0 && (c.b < 0 || (c.b == 0 && c.c < 0)))) continue;
      const ld sx = c.a * (ld)L_.x(), sy = c.b * (ld)L_.y(), sz = c.c * (ld)L_.z();
      ld f = 0;
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j) {
          if (c.r == 0 && i == j) continue;
          f += phi(x_[j] - x_[i] + sx, y_[j] - y_[i] + sy, z_[j] - z_[i] + sz);
        }
      F_[q] = (c.r == 0) ? f : 2 * f;
    }
  }

  /// βU_tinfoil for cut-off radius R (in units of the shortest edge), smooth or sharp.
  ld tinfoil(double R_boxes, double gamma, bool smooth = true) const {
    const ld R = R_boxes * L_.minCoeff();
    ld sum = 0;
    for (std::size_t q = 0; q < cells_.size(); ++q) {
      if (cells_[q].r > R) continue;
      sum += (smooth ? taper(cells_[q].r / R) : 1.0L) * F_[q];
    }
    const ld n = x_.size(), V = (ld)L_.prod();
    return gamma / 2 * (sum / 2 - 2 * kPiL / (3 * V) * n * n);
  }

  /// βU change when dipole i (index among the dipoles) moves from ro to rn (smooth cut-off R).
  ld delta(std::size_t i, const Vec3& ro, const Vec3& rn, double R_boxes, double gamma) const {
    const ld R = R_boxes * L_.minCoeff();
    ld sum = 0;
    for (const Cell& c : cells_) {
      if (c.r > R) continue;
      const ld w = taper(c.r / R);
      const ld sx = c.a * (ld)L_.x(), sy = c.b * (ld)L_.y(), sz = c.c * (ld)L_.z();
      ld f = 0;
      for (std::size_t j = 0; j < x_.size(); ++j) {
        if (j == i) continue;
        f += phi(x_[j] + sx - rn.x(), y_[j] + sy - rn.y(), z_[j] + sz - rn.z()) -
             phi(x_[j] + sx - ro.x(), y_[j] + sy - ro.y(), z_[j] + sz - ro.z());
      }
      sum += w * f;
    }
    return gamma / 2 * sum;
  }

 private:
  struct Cell {
    ld r;
    int a, b, c;
  };
  Vec3 L_, E_;
  ld rmax_ = 0;
  std::vector<Cell> cells_;
  std::vector<ld> x_, y_, z_, F_;
};

/// κ for a real-space cut-off r_cut and accuracy, from the public error estimate (bisection).
double kappa_for(const Vec3& L, std::size_t n, double r_cut, double accuracy) {
  double lo = 1.3 / r_cut, hi = 7.0 / r_cut;
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (ewald_real_space_error(L, n, mid, r_cut) <= accuracy ? hi : lo) = mid;
  }
  return hi;
}

struct Case {
  const char* name;
  Vec3 L, E;
  std::size_t n;
  double r_max;         // brute-force radius in shortest edges
  bool sharp_converges;  // the sharp spherical sum's dipole term cancels shell by shell (cubic, or Ê ∥ (1,1,1))
};

}  // namespace

// ---- 1. Ewald total energy against the brute-force spherical lattice sum ---------------------------

TEST(DipolarEwald, TotalEnergyMatchesBruteForceLatticeSum) {
  const Case cases[] = {
      {"cubic 8, N=24, oblique field", Vec3(8, 8, 8), Vec3(0.3, -0.5, 0.8), 24, 30, true},
      {"7x8x9.5, N=40, field (1,1,1)", Vec3(7, 8, 9.5), Vec3(1, 1, 1), 40, 30, true},
      {"7x9x8, N=20, field along z", Vec3(7, 9, 8), Vec3(0, 0, 1), 20, 40, false},
      {"cubic 10, N=60, field along x", Vec3(10, 10, 10), Vec3(1, 0, 0), 60, 25, true},
  };
  std::uint64_t seed = 100;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const Particles p = random_configuration(c.L, c.n, ++seed);
    const std::vector<char> mask(c.n, 1);
    BruteForce bf(c.L, c.E, c.r_max);
    bf.load(p, mask);
    const double scale = c.n * kGamma / 2;  // N γ/2
    // Convergence of the reference: two successive radii agree to 1e-8 of the scale.
    const ld u1 = bf.tinfoil(c.r_max - 5, kGamma), u2 = bf.tinfoil(c.r_max, kGamma);
    const ld sharp = bf.tinfoil(c.r_max, kGamma, false);
    std::printf("  [%s] brute force R=%g: %.12Lf, R=%g: %.12Lf (diff %.1Le of N·γ/2; sharp cut %.1Le)\n", c.name,
                c.r_max - 5, u1, c.r_max, u2, std::fabs(u2 - u1) / scale, std::fabs(sharp - u2) / scale);
    ASSERT_LE(std::fabs(u2 - u1), 1e-8 * scale);
    // The sharp spherical sum has the same limit but converges slowly (~R⁻³ with lattice noise) when
    // the macroscopic dipole term cancels shell by shell, and much more slowly (~R⁻¹) otherwise.
    if (c.sharp_converges) {
      EXPECT_LE(std::fabs(sharp - u2), 1e-6 * scale);
    }
    for (double acc : {1e-5, 1e-7}) {
      const EwaldParameters ep = choose_ewald_parameters(c.L, c.n, acc);
      DipolarEwald ew(c.L, c.E, kGamma, ep, mask);
      const double u = ew.total_energy(p);
      const double err = std::fabs(u - static_cast<double>(u2));
      std::printf("    accuracy %.0e: kappa %.4f r_cut %.3f n_max %d (%zu k) U = %.12f, |U - U_bf| = %.2e of N·γ/2"
                  " (%.1e of |U|)\n",
                  acc, ep.kappa, ep.r_cut, ep.n_max, ew.wave_vector_count(), u, err / scale,
                  err / std::fabs(u));
      EXPECT_LE(err, acc * scale) << "accuracy " << acc;
    }
  }
}

TEST(DipolarEwald, TinfoilSurfaceTermForOneDipolePerBox) {
  // One dipole per box: the spherical (vacuum) lattice sum vanishes by symmetry for a cubic box (any
  // field direction) and for an orthorhombic box with Ê ∥ (1,1,1) (the sum is diagonal and
  // traceless), so tinfoil = −(γ/2)(2π/(3V)). Checked against both the brute force and the formula.
  const Case cases[] = {{"cubic", Vec3(6, 6, 6), Vec3(0.2, 0.9, -0.4), 1, 30, true},
                        {"orthorhombic", Vec3(5, 6, 7.5), Vec3(1, 1, 1), 1, 30, true}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    Particles p;
    p.add(0, Vec3(1.3, 2.2, 0.7), Quat::Identity(), 0);
    const std::vector<char> mask{1};
    BruteForce bf(c.L, c.E, c.r_max);
    bf.load(p, mask);
    const double expected = -kGamma / 2 * 2 * M_PI / (3 * c.L.prod());
    EXPECT_NEAR(static_cast<double>(bf.tinfoil(c.r_max, kGamma)), expected, 1e-10 * kGamma / 2);
    DipolarEwald ew(c.L, c.E, kGamma, choose_ewald_parameters(c.L, 1, 1e-7), mask);
    EXPECT_NEAR(ew.total_energy(p), expected, 1e-7 * kGamma / 2);
  }
  // A non-symmetric case: the surface term is the only difference between the two boundaries, so a
  // wrong sign or factor would show as (2π/(3V)) N² γ/2 ≈ 13 here.
  const Vec3 L(7, 8, 9.5);
  const Particles p = random_configuration(L, 30, 77);
  const std::vector<char> mask(30, 1);
  BruteForce bf(L, Vec3::UnitZ(), 35);
  bf.load(p, mask);
  const double surface = kGamma / 2 * 2 * M_PI / (3 * L.prod()) * 30 * 30;
  DipolarEwald ew(L, Vec3::UnitZ(), kGamma, choose_ewald_parameters(L, 30, 1e-7), mask);
  const double vac = static_cast<double>(bf.tinfoil(35, kGamma)) + surface;
  EXPECT_NEAR(ew.total_energy(p) + surface, vac, 1e-7 * 30 * kGamma / 2);
  EXPECT_GT(std::fabs(ew.total_energy(p) - vac), 0.5 * surface);
}

// ---- ΔU accuracy against the brute force (what enters the MC acceptance) ------------------------

TEST(DipolarEwald, DeltaEnergyMatchesBruteForce) {
  const Vec3 L(9, 8, 10);
  const std::size_t n = 40;
  const Particles p0 = random_configuration(L, n, 314);
  const std::vector<char> mask(n, 1);
  BruteForce bf(L, Vec3(0.1, 0.2, 1), 25);
  bf.load(p0, mask);
  Rng rng(9, 9);
  for (double acc : {1e-5, 1e-7}) {
    DipolarEwald ew(L, Vec3(0.1, 0.2, 1), kGamma, choose_ewald_parameters(L, n, acc), mask);
    ew.rebuild(p0);
    double sum2 = 0, worst = 0;
    const int moves = 8;
    for (int m = 0; m < moves; ++m) {
      const std::size_t i = rng.index(n);
      // a far move (new position anywhere at ≥ 1 from the others): the largest ΔU truncation error
      Vec3 r;
      for (bool ok = false; !ok;) {
        r = Vec3(rng.uniform(0, L.x()), rng.uniform(0, L.y()), rng.uniform(0, L.z()));
        ok = true;
        for (std::size_t j = 0; j < n && ok; ++j) {
          if (j == i) continue;
          Vec3 d = r - p0.position(j);
          for (int a = 0; a < 3; ++a) d[a] -= L[a] * std::round(d[a] / L[a]);
          ok = d.norm() >= 1.0;
        }
      }
      const double du = ew.delta_energy(p0, i, r);
      const double ref = static_cast<double>(bf.delta(i, p0.position(i), r, 25, kGamma));
      const double e = std::fabs(du - ref) / (kGamma / 2);
      sum2 += e * e;
      worst = std::max(worst, e);
    }
    std::printf("  accuracy %.0e: ΔU error (units of γ/2) rms %.2e, max %.2e\n", acc, std::sqrt(sum2 / moves), worst);
    // per-particle estimate ≤ acc, and ΔU of a far move is a difference of two particle energies
    EXPECT_LE(std::sqrt(sum2 / moves), std::sqrt(2.0) * acc);
    EXPECT_LE(worst, 4 * acc);
  }
}

// ---- 2. κ independence ------------------------------------------------------------------------------

TEST(DipolarEwald, EnergyIndependentOfKappa) {
  const Vec3 L(11, 12, 13);
  const std::size_t n = 50;
  const Particles p = random_configuration(L, n, 2718);
  const std::vector<char> mask(n, 1);
  const Vec3 E(0.4, -0.3, 0.8);
  for (double acc : {1e-5, 1e-7}) {
    std::vector<EwaldParameters> sets;
    sets.push_back(choose_ewald_parameters(L, n, acc));  // r_cut = L/2
    EwaldParameters b = sets[0];                            // larger κ, same r_cut
    b.kappa *= 1.3;
    b.n_max = ewald_n_max_for(L, n, b.kappa, acc);
    sets.push_back(b);
    EwaldParameters c;                                      // shorter r_cut
    c.r_cut = 0.35 * L.minCoeff();
    c.kappa = kappa_for(L, n, c.r_cut, acc);
    c.n_max = ewald_n_max_for(L, n, c.kappa, acc);
    sets.push_back(c);
    std::vector<double> u;
    for (const EwaldParameters& ep : sets) {
      DipolarEwald ew(L, E, kGamma, ep, mask);
      u.push_back(ew.total_energy(p));
      std::printf("  accuracy %.0e: kappa %.4f r_cut %.3f n_max %d -> U = %.12f\n", acc, ep.kappa, ep.r_cut, ep.n_max,
                  u.back());
    }
    for (std::size_t k = 1; k < u.size(); ++k) EXPECT_NEAR(u[k], u[0], acc * n * kGamma / 2) << "set " << k;
  }
}

// ---- 3. Two dipoles in a large box ---------------------------------------------------------------

TEST(DipolarEwald, TwoDipolesInLargeBoxReproduceThePairFormula) {
  // Tinfoil − bare pair = image terms (O(r²/L⁵) after spherical summation in a cubic box) minus
  // the surface term (γ/2)(2π/(3V))·4 = (8π/3)(r/L)³ · (γ/2)/r³, for either geometry: an
  // O((r/L)³) deviation on the pair-energy scale (γ/2)/r³. Tolerance 10 (r/L)³ (γ/2)/r³; with the
  // surface term added back, the remaining image terms are O((r/L)⁵) (measured coefficient ≈ 40).
  const double r = 1.5;
  const Vec3 E(0, 0, 1);
  for (double Ledge : {20.0, 40.0}) {
    const Vec3 L(Ledge, Ledge, Ledge);
    const std::vector<char> mask{1, 1};
    DipolarEwald ew(L, E, kGamma, choose_ewald_parameters(L, 2, 1e-7), mask);
    const double surface = kGamma / 2 * 2 * M_PI / (3 * L.prod()) * 4;
    for (int geometry = 0; geometry < 2; ++geometry) {
      Particles p;
      const Vec3 a(3.1, 4.2, 5.3);
      const Vec3 d = geometry == 0 ? Vec3(0, 0, r) : Vec3(r, 0, 0);  // head-to-tail, side-by-side
      p.add(0, a, Quat::Identity(), 0);
      p.add(0, a + d, Quat::Identity(), 1);
      const double bare = dipolar_pair_energy(d, E, kGamma);
      EXPECT_NEAR(bare, geometry == 0 ? -kGamma / (r * r * r) : kGamma / 2 / (r * r * r), 1e-12);
      const double u = ew.total_energy(p);
      const double pair_scale = kGamma / 2 / (r * r * r);
      EXPECT_NEAR(u, bare, 10 * std::pow(r / Ledge, 3) * pair_scale) << "L = " << Ledge << " geometry " << geometry;
      EXPECT_GT(std::fabs(u - bare), 0.5 * surface);  // the surface term is really there
      EXPECT_NEAR(u + surface, bare, 100 * std::pow(r / Ledge, 5) * pair_scale + 1e-7 * kGamma);
      std::printf("  L = %g, %s: U = %.10f, bare %.10f, (U − bare)/surface = %.6f\n", Ledge,
                  geometry == 0 ? "head-to-tail" : "side-by-side", u, bare, (u - bare) / surface);
    }
  }
}

// ---- 4. Incremental updates, structure factor, checkpoints ---------------------------------------

TEST(DipolarEwald, DeltaEnergyEqualsDifferenceOfTotals) {
  // 60 dipoles and one probe sphere (no dipole). Tolerance: 1e-10 of the magnitude of the
  // components of the total, |U − U_const| + |U_const| + γ/2 (the rounding of two totals of
  // that size; γ/2 keeps it meaningful when they are small).
  const Vec3 L(12, 11, 13);
  const std::size_t n = 61;
  Particles p = random_configuration(L, n, 4242);
  std::vector<char> mask(n, 1);
  mask[17] = 0;
  DipolarEwald ew(L, Vec3(1, 2, 3), kGamma, choose_ewald_parameters(L, 60, 1e-5), mask);
  ew.rebuild(p);
  Rng rng(3, 1);
  double u = ew.total_energy(p);
  int accepted = 0;
  double worst = 0;
  for (int m = 0; m < 200; ++m) {
    const std::size_t i = rng.index(n);
    Vec3 r = p.position(i) + Vec3(rng.uniform(-0.8, 0.8), rng.uniform(-0.8, 0.8), rng.uniform(-0.8, 0.8));
    for (int a = 0; a < 3; ++a) r[a] -= L[a] * std::floor(r[a] / L[a]);
    const double du = ew.delta_energy(p, i, r);
    Particles q = p;
    q.set_position(i, r);
    const double u_new = ew.total_energy(q);
    const double scale = std::fabs(u - ew.constant_energy()) + std::fabs(ew.constant_energy()) + kGamma / 2;
    worst = std::max(worst, std::fabs(du - (u_new - u)) / scale);
    EXPECT_NEAR(du, u_new - u, 1e-10 * scale) << "move " << m;
    if (i == 17) {
      EXPECT_EQ(du, 0.0);
    }
    if (rng.uniform() < 0.6) {
      ew.accept(i);
      p = q;
      u = u_new;
      ++accepted;
    }
  }
  std::printf("  %d of 200 moves accepted; worst |ΔU − (U_after − U_before)| = %.1e of the scale\n", accepted, worst);
  // S(k) after the accepted moves equals a rebuild from scratch.
  const std::vector<double> s_inc = ew.structure_factor();
  DipolarEwald fresh(L, Vec3(1, 2, 3), kGamma, choose_ewald_parameters(L, 60, 1e-5), mask);
  fresh.rebuild(p);
  const std::vector<double> s_new = fresh.structure_factor();
  ASSERT_EQ(s_inc.size(), 2 * ew.wave_vector_count());
  double dmax = 0;
  for (std::size_t k = 0; k < s_inc.size(); ++k) dmax = std::max(dmax, std::fabs(s_inc[k] - s_new[k]));
  EXPECT_LE(dmax, 1e-12 * 60) << "|S| ≤ N";
  std::printf("  max |S_incremental − S_rebuilt| = %.1e (N = 60)\n", dmax);
}

TEST(DipolarEwald, StructureFactorRoundTripIsBitIdentical) {
  const Vec3 L(10, 10, 10);
  const std::size_t n = 40;
  Particles p = random_configuration(L, n, 99);
  const std::vector<char> mask(n, 1);
  const EwaldParameters ep = choose_ewald_parameters(L, n, 1e-5);
  DipolarEwald a(L, Vec3::UnitZ(), kGamma, ep, mask);
  a.rebuild(p);
  Rng rng(5, 5);
  auto random_move = [&](Rng& g, const Particles& q) {
    const std::size_t i = g.index(n);
    Vec3 r = q.position(i) + Vec3(g.uniform(-0.3, 0.3), g.uniform(-0.3, 0.3), g.uniform(-0.3, 0.3));
    for (int k = 0; k < 3; ++k) r[k] -= L[k] * std::floor(r[k] / L[k]);
    return std::make_pair(i, r);
  };
  for (int m = 0; m < 300; ++m) {  // some history
    auto [i, r] = random_move(rng, p);
    a.delta_energy(p, i, r);
    a.accept(i);
    p.set_position(i, r);
  }
  const std::vector<double> saved = a.structure_factor();
  DipolarEwald b(L, Vec3::UnitZ(), kGamma, ep, mask);  // "restarted" object
  b.set_structure_factor(saved);
  Particles pb = p;
  Rng ra(11, 0), rb(11, 0);
  for (int m = 0; m < 100; ++m) {
    auto [i, r] = random_move(ra, p);
    auto [ib, rbv] = random_move(rb, pb);
    const double da = a.delta_energy(p, i, r);
    const double db = b.delta_energy(pb, ib, rbv);
    ASSERT_EQ(da, db) << "move " << m;  // bit for bit
    if (m % 2 == 0) {
      a.accept(i);
      b.accept(ib);
      p.set_position(i, r);
      pb.set_position(ib, rbv);
    }
  }
  EXPECT_EQ(a.structure_factor(), b.structure_factor());
  EXPECT_THROW(b.set_structure_factor(std::vector<double>(3)), InputError);
}

TEST(DipolarEwald, AcceptBookkeeping) {
  const Vec3 L(8, 8, 8);
  Particles p = random_configuration(L, 10, 1);
  std::vector<char> mask(10, 1);
  mask[3] = 0;
  DipolarEwald ew(L, Vec3::UnitX(), kGamma, choose_ewald_parameters(L, 9, 1e-5), mask);
  ew.rebuild(p);
  EXPECT_THROW(ew.accept(0), std::logic_error);  // nothing pending
  ew.delta_energy(p, 2, Vec3(1, 1, 1));
  EXPECT_THROW(ew.accept(5), std::logic_error);  // another particle
  ew.delta_energy(p, 2, Vec3(1, 1, 1));
  ew.accept(2);
  EXPECT_THROW(ew.accept(2), std::logic_error);  // already committed
  // the probe (no dipole) neither has nor feels dipolar energy, and its "move" leaves S(k) alone
  const std::vector<double> s0 = ew.structure_factor();
  EXPECT_EQ(ew.delta_energy(p, 3, Vec3(4, 4, 4)), 0.0);
  ew.accept(3);
  EXPECT_EQ(ew.structure_factor(), s0);
  Particles wrong = p;
  wrong.pop_back();
  EXPECT_THROW(ew.delta_energy(wrong, 0, Vec3(1, 1, 1)), std::invalid_argument);
  // γ enters linearly; set_gamma (field switching) keeps S(k)
  const double u13 = ew.total_energy(p);
  ew.set_gamma(2 * kGamma);
  EXPECT_NEAR(ew.total_energy(p), 2 * u13, 1e-12 * std::fabs(u13));
  EXPECT_EQ(ew.structure_factor(), s0);
}

TEST(DipolarEwald, WaveVectorCountAndRealSpaceFunction) {
  // Cubic box: the half space of |n|² ≤ n_max² holds (#lattice points in the ball − 1)/2 vectors.
  const Vec3 L(9, 9, 9);
  EwaldParameters ep;
  ep.kappa = 0.8;
  ep.r_cut = 4.5;
  ep.n_max = 7;
  DipolarEwald ew(L, Vec3(0.3, 0.4, 0.5), kGamma, ep, std::vector<char>(2, 1));
  std::size_t ball = 0;
  for (int a = -7; a <= 7; ++a)
    for (int b = -7; b <= 7; ++b)
      for (int c = -7; c <= 7; ++c) ball += (a * a + b * b + c * c <= 49);
  EXPECT_EQ(ew.wave_vector_count(), (ball - 1) / 2);
  // The polynomial real-space ψ against the closed form in long double. ψ = bare + remainder, and
  // near r_cut the two cancel to erfc(κr), so the error is measured against the size of the parts:
  // (1 + 3(Ê·d̂)²)/r³ for the bare part plus κ³ for the remainder (b(0) = −4κ³/(3√π)).
  const Vec3 E = Vec3(0.3, 0.4, 0.5).normalized();
  Rng rng(1, 2);
  double worst = 0;
  for (int m = 0; m < 2000; ++m) {
    const Vec3 d = Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)).normalized() *
                   rng.uniform(0.05, 4.49);
    const ld s = d.squaredNorm(), r = std::sqrt(s), x = 0.8L * r, k = 0.8L;
    const ld B = std::erfc(x) / (s * r) + 2 / std::sqrt(kPiL) * k * std::exp(-x * x) / s;
    const ld C = 3 * std::erfc(x) / (s * s * r) + 2 / std::sqrt(kPiL) * k * (2 * k * k + 3 / s) * std::exp(-x * x) / s;
    const ld ed = E.dot(d);
    const ld exact = B - ed * ed * C;
    const ld size = (1 + 3 * ed * ed / s) / (s * r) + k * k * k;
    worst = std::max(worst, static_cast<double>(std::fabs(ew.real_space_psi(d) - exact) / size));
  }
  std::printf("  real-space polynomial degree %d, worst error of ψ %.1e of (1 + 3(Ê·d̂)²)/r³ + κ³\n", ew.real_space_degree(),
              worst);
  EXPECT_LE(worst, 1e-14);
  EXPECT_EQ(ew.real_space_psi(Vec3(3.3, 3.3, 0)), 0.0);  // beyond r_cut (4.67 > 4.5)
  EXPECT_NE(ew.real_space_psi(Vec3(4.4, 0, 0)), 0.0);
}

// ---- 5. Bare pair energy (spec §6.1 worked values) ----------------------------------------------

TEST(DipolarEwald, PairEnergyWorkedValues) {
  const Vec3 E(0, 0, 1);
  EXPECT_NEAR(dipolar_pair_energy(Vec3(0, 0, 1), E, 13.0), -13.0, 1e-12);
  EXPECT_NEAR(dipolar_pair_energy(Vec3(0, 0, -1), E, 13.0), -13.0, 1e-12);
  EXPECT_NEAR(dipolar_pair_energy(Vec3(1, 0, 0), E, 13.0), 6.5, 1e-12);
  EXPECT_NEAR(dipolar_pair_energy(Vec3(0, 1, 0), E, 13.0), 6.5, 1e-12);
  const double rt = std::cbrt(13.0 / 3.2);
  EXPECT_NEAR(rt, 1.5956, 5e-5);
  EXPECT_NEAR(dipolar_pair_energy(Vec3(0, 0, rt), E, 13.0), -3.2, 1e-12);
  EXPECT_LT(dipolar_pair_energy(Vec3(0, 0, rt - 1e-6), E, 13.0), -3.2);
  EXPECT_GT(dipolar_pair_energy(Vec3(0, 0, rt + 1e-6), E, 13.0), -3.2);
  // magic angle: zero
  const double th = std::acos(1 / std::sqrt(3.0));
  EXPECT_NEAR(dipolar_pair_energy(Vec3(std::sin(th), 0, std::cos(th)) * 1.3, E, 13.0), 0.0, 1e-12);
  EXPECT_EQ(dipolar_pair_energy(Vec3(0, 0, 1), E, 0.0), 0.0);
  // σ scales lengths: βu(σ r; σ) = βu(r; 1)
  EXPECT_NEAR(dipolar_pair_energy(Vec3(0, 0, 2.5), E, 13.0, 2.5), -13.0, 1e-12);
}

// ---- 6. Minimum-image smoke-test mode -------------------------------------------------------------

TEST(DipolarEwald, MinimumImageOnlyIsTheBarePairSum) {
  const Vec3 L(9, 10, 11);
  const std::size_t n = 40;
  Particles p = random_configuration(L, n, 8);
  std::vector<char> mask(n, 1);
  mask[0] = 0;
  const Vec3 E(1, -1, 2);
  EwaldParameters ep;
  ep.minimum_image_only = true;
  DipolarEwald ew(L, E, kGamma, ep, mask);
  EXPECT_EQ(ew.wave_vector_count(), 0u);
  EXPECT_EQ(ew.parameters().r_cut, 4.5);
  auto bare_sum = [&](const Particles& q) {
    double u = 0;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) {
        if (!mask[i] || !mask[j]) continue;
        Vec3 d = q.position(j) - q.position(i);
        for (int a = 0; a < 3; ++a) d[a] -= L[a] * std::round(d[a] / L[a]);
        if (d.norm() < 4.5) u += dipolar_pair_energy(d, E.normalized(), kGamma);
      }
    return u;
  };
  const double u0 = bare_sum(p);
  EXPECT_NEAR(ew.total_energy(p), u0, 1e-12 * n * kGamma);
  EXPECT_EQ(ew.constant_energy(), 0.0);
  Rng rng(4, 4);
  for (int m = 0; m < 20; ++m) {
    const std::size_t i = 1 + rng.index(n - 1);
    Vec3 r = p.position(i) + Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    for (int a = 0; a < 3; ++a) r[a] -= L[a] * std::floor(r[a] / L[a]);
    Particles q = p;
    q.set_position(i, r);
    EXPECT_NEAR(ew.delta_energy(p, i, r), bare_sum(q) - bare_sum(p), 1e-11 * n * kGamma);
    ew.accept(i);
    p = q;
  }
}

// ---- 7. Parameters and errors ---------------------------------------------------------------------

TEST(DipolarEwald, BadParametersAreInputErrors) {
  const Vec3 L(10, 10, 10);
  for (double acc : {0.0, -1e-5, 0.1, 0.5, std::nan("")}) {
    const InputError e = input_error([&] { choose_ewald_parameters(L, 100, acc); });
    EXPECT_EQ(e.json_path(), "ewald.accuracy");
    EXPECT_NE(std::string(e.what()).find("expected"), std::string::npos) << e.what();
  }
  EXPECT_EQ(input_error([&] { choose_ewald_parameters(L, 100, 1e-30); }).json_path(), "ewald.accuracy");  // κ r_cut > 7
  EXPECT_NO_THROW(choose_ewald_parameters(L, 100, 0.0999));
  EXPECT_NO_THROW(choose_ewald_parameters(L, 100, 1e-12));
  const std::vector<char> mask(3, 1);
  EwaldParameters ok = choose_ewald_parameters(L, 3, 1e-5);
  auto bad = [&](EwaldParameters ep) { return input_error([&] { DipolarEwald(L, Vec3::UnitZ(), 13, ep, mask); }); };
  EwaldParameters b = ok;
  b.kappa = -1;
  EXPECT_EQ(bad(b).json_path(), "ewald.kappa");
  b = ok;
  b.r_cut = 5.01;  // > L/2
  EXPECT_EQ(bad(b).json_path(), "ewald.r_cut");
  b = ok;
  b.n_max = 0;
  EXPECT_EQ(bad(b).json_path(), "ewald.n_max");
  b = ok;
  b.kappa = 7.5 / b.r_cut;
  EXPECT_EQ(bad(b).json_path(), "ewald.kappa");
  b = ok;
  b.kappa = 6.99 / b.r_cut;  // near the largest allowed κ r_cut = 7: the polynomial still reaches 1e-15
  b.n_max = 40;
  EXPECT_NO_THROW(DipolarEwald(L, Vec3::UnitZ(), 13, b, mask));
  EXPECT_EQ(input_error([&] { DipolarEwald(L, Vec3::Zero(), 13, ok, mask); }).json_path(), "field.direction");
  EXPECT_EQ(input_error([&] { DipolarEwald(Vec3(10, -1, 10), Vec3::UnitZ(), 13, ok, mask); }).json_path(),
            "box.edges");
}

TEST(DipolarEwald, ParametersForTheStudySystems) {
  // (L, N) of the two benchmark systems (η = 0.02 of unit cubes) at the default accuracy 1e-5.
  struct S {
    double L;
    std::size_t n;
  };
  for (S s : {S{42.17, 1500}, S{18.42, 125}}) {
    const Vec3 L(s.L, s.L, s.L);
    const EwaldParameters ep = choose_ewald_parameters(L, s.n);
    DipolarEwald ew(L, Vec3::UnitZ(), kGamma, ep, std::vector<char>(s.n, 1));
    std::printf("  L = %.2f, N = %zu: kappa = %.6f, r_cut = %.4f (kappa r_cut = %.4f), n_max = %d, %zu k-vectors,"
                " degree %d, est. errors real %.1e recip %.1e\n",
                s.L, s.n, ep.kappa, ep.r_cut, ep.kappa * ep.r_cut, ep.n_max, ew.wave_vector_count(),
                ew.real_space_degree(), ewald_real_space_error(L, s.n, ep.kappa, ep.r_cut),
                ewald_reciprocal_error(L, s.n, ep.kappa, 2 * M_PI * ep.n_max / s.L));
    EXPECT_DOUBLE_EQ(ep.r_cut, s.L / 2);
    const double part = 1e-5 / std::sqrt(2.0);  // each part, so that the combined estimate is ≤ 1e-5
    EXPECT_LE(ewald_real_space_error(L, s.n, ep.kappa, ep.r_cut), part * (1 + 1e-9));
    EXPECT_GT(ewald_real_space_error(L, s.n, ep.kappa * (1 - 1e-6), ep.r_cut), part);
    EXPECT_LE(ewald_reciprocal_error(L, s.n, ep.kappa, 2 * M_PI * ep.n_max / s.L), part);
    EXPECT_GT(ewald_reciprocal_error(L, s.n, ep.kappa, 2 * M_PI * (ep.n_max - 1) / s.L), part);
  }
}

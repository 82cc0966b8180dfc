// The closed-form hydrodynamic reference (tests/support/hydro_theory.hpp) against independent
// numbers: the sphere (Stokes, Kirchhoff), the disk limits of the spheroid (Oberbeck 1876 /
// Lamb), the spheroid factor table of spec 70-theory.md §7.3 and the Tirado–García de la Torre
// cylinder table of spec 70-theory.md §6.2.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "hydro_theory.hpp"

using namespace anisodyn::theory;

namespace {

// Half a unit of the last digit of a printed decimal such as "0.0022" or "133.68".
double half_unit_of_last_digit(const std::string& printed) {
  const auto dot = printed.find('.');
  const int decimals = dot == std::string::npos ? 0 : static_cast<int>(printed.size() - dot - 1);
  return 0.5 * std::pow(10.0, -decimals);
}

// |computed − printed| within max(relative `rel`, half-unit of the last printed digit).
::testing::AssertionResult matches_printed(double computed, const std::string& printed, double rel) {
  const double value = std::stod(printed);
  const double tol = std::max(rel * std::abs(value), half_unit_of_last_digit(printed)) * (1 + 1e-9);
  if (std::abs(computed - value) <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "computed " << computed << " vs printed " << printed
                                       << " (|diff| " << std::abs(computed - value) << " > tol " << tol << ")";
}

// Spheroid with the symmetry semi-axis a along body z and equatorial semi-axes c along x, y.
struct SpheroidFactors {
  double A, B, t_ax, t_perp, r_ax, r_perp, R_eff_t;
};

SpheroidFactors spheroid_factors(double a, double c) {
  const auto xt = ellipsoid_translational_friction(c, c, a);  // η = 1
  const auto xr = ellipsoid_rotational_friction(c, c, a);
  const double Rz_t = xt[2] / (6 * kPi), Rx_t = xt[0] / (6 * kPi);
  const double Rz_r3 = xr[2] / (8 * kPi), Rx_r3 = xr[0] / (8 * kPi);
  // Orientational averages: harmonic mean of the radii (mean mobility), and likewise for R³.
  const double R_eff_t = 3.0 / (1.0 / Rz_t + 2.0 / Rx_t);
  const double R_eff_r3 = 3.0 / (1.0 / Rz_r3 + 2.0 / Rx_r3);
  return {a / R_eff_t, a * a * a / R_eff_r3, Rz_t / c, Rx_t / c, Rz_r3 / (c * c * c), Rx_r3 / (c * c * c),
          R_eff_t};
}

}  // namespace

// ---- sphere ----------------------------------------------------------------------------------------

TEST(HydroTheorySphere, EllipsoidWithEqualSemiAxesGivesStokesAndRotationalStokesFriction) {
  for (double R : {0.3, 1.0, 4.25, 17.0}) {
    const double eta = 0.7;
    const auto xt = ellipsoid_translational_friction(R, R, R, eta);
    const auto xr = ellipsoid_rotational_friction(R, R, R, eta);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(xt[i] / (6 * kPi * eta * R), 1.0, 1e-8) << "R=" << R << " axis " << i;
      EXPECT_NEAR(xr[i] / (8 * kPi * eta * R * R * R), 1.0, 1e-8) << "R=" << R << " axis " << i;
    }
  }
}

TEST(HydroTheorySphere, EllipsoidIntegralsOfSphereHaveClosedForm) {
  // χ = ∫ds (R²+s)^{-3/2} = 2/R,  P = ∫ds (R²+s)^{-5/2} = 2/(3R³).
  const double R = 2.5;
  const auto I = ellipsoid_integrals(R, R, R);
  EXPECT_NEAR(I.chi * R / 2, 1.0, 1e-10);
  for (double P : I.P) EXPECT_NEAR(P * 3 * R * R * R / 2, 1.0, 1e-10);
}

TEST(HydroTheorySphere, StokesEinsteinAndDebyeMatchEllipsoidDiffusionOfSphere) {
  const double R = 1.7;
  const auto d = ellipsoid_diffusion(R, R, R);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(d.D_trans[i] / stokes_einstein_diffusion(R), 1.0, 1e-8);
    EXPECT_NEAR(d.D_rot[i] / stokes_einstein_debye_rotational_diffusion(R), 1.0, 1e-8);
  }
  EXPECT_DOUBLE_EQ(stokes_einstein_diffusion(R, 2.0, 3.0), 3.0 / (6 * kPi * 2.0 * R));
  EXPECT_DOUBLE_EQ(stokes_einstein_debye_rotational_diffusion(R, 2.0, 3.0), 3.0 / (8 * kPi * 2.0 * R * R * R));
}

// ---- spheroid factor table (spec 70 §7.3; definitions in spec 40 §8.6) -----------------------------

TEST(HydroTheorySpheroid, FactorTableOfSpec70Section7_3AtConstantVolume) {
  // Columns as printed: φ = a/c, A, B, t_ax, t_perp, r_ax, r_perp, R_eff,t (nm); a c² = 4.25³ nm³.
  struct Row {
    double num, den;
    const char* A; const char* B; const char* t_ax; const char* t_perp;
    const char* r_ax; const char* r_perp; const char* R_eff_t;
  };
  const Row rows[] = {
      {1, 10, "0.1478", "0.0022", "0.8525", "0.6133", "0.4789", "0.4305", "6.195"},
      {1, 5, "0.2795", "0.0169", "0.8615", "0.6596", "0.5344", "0.4480", "5.200"},
      {1, 4, "0.3403", "0.0319", "0.8673", "0.6823", "0.5624", "0.4608", "4.956"},
      {1, 3, "0.4352", "0.0708", "0.8787", "0.7197", "0.6095", "0.4882", "4.695"},
      {1, 2, "0.6046", "0.2064", "0.9053", "0.7927", "0.7050", "0.5658", "4.428"},
      {2, 3, "0.7523", "0.4156", "0.9352", "0.8636", "0.8021", "0.6754", "4.311"},
      {4, 5, "0.8580", "0.6271", "0.9606", "0.9189", "0.8807", "0.7877", "4.269"},
      {9, 10, "0.9313", "0.8064", "0.9801", "0.9597", "0.9402", "0.8870", "4.254"},
      {10, 9, "1.0717", "1.2292", "1.0223", "1.0441", "1.0669", "1.1423", "4.254"},
      {5, 4, "1.1552", "1.5330", "1.0505", "1.0985", "1.1510", "1.3460", "4.269"},
      {3, 2, "1.2912", "2.1197", "1.1017", "1.1942", "1.3037", "1.7902", "4.313"},
      {2, 1, "1.5207", "3.4248", "1.2039", "1.3789", "1.6134", "3.0099", "4.436"},
      {3, 1, "1.8697", "6.5741", "1.4045", "1.7276", "2.2439", "7.0223", "4.728"},
      {4, 1, "2.1311", "10.538", "1.5979", "2.0565", "2.8842", "13.583", "5.025"},
      {5, 1, "2.3397", "15.394", "1.7848", "2.3710", "3.5304", "23.203", "5.311"},
      {10, 1, "3.0083", "53.973", "2.6471", "3.8115", "6.8047", "133.68", "6.557"},
  };
  constexpr double kRel = 6e-4;
  const double V = std::pow(4.25, 3);
  for (const Row& r : rows) {
    const double phi = r.num / r.den;
    const double c = std::cbrt(V / phi), a = phi * c;
    const SpheroidFactors f = spheroid_factors(a, c);
    SCOPED_TRACE("phi = " + std::to_string(r.num) + "/" + std::to_string(r.den));
    EXPECT_TRUE(matches_printed(f.A, r.A, kRel)) << "A";
    EXPECT_TRUE(matches_printed(f.B, r.B, kRel)) << "B";
    EXPECT_TRUE(matches_printed(f.t_ax, r.t_ax, kRel)) << "t_ax";
    EXPECT_TRUE(matches_printed(f.t_perp, r.t_perp, kRel)) << "t_perp";
    EXPECT_TRUE(matches_printed(f.r_ax, r.r_ax, kRel)) << "r_ax";
    EXPECT_TRUE(matches_printed(f.r_perp, r.r_perp, kRel)) << "r_perp";
    EXPECT_TRUE(matches_printed(f.R_eff_t, r.R_eff_t, kRel)) << "R_eff,t";
  }
}

TEST(HydroTheorySpheroid, PerrinClosedFormOfLabFrameFactorsAMatchesIntegrals) {
  // Perrin's closed forms (spec 40 §8.6): A = arctan(√(φ⁻²−1))/√(φ⁻²−1) (oblate),
  // ln(φ+√(φ²−1))/√(1−φ⁻²) (prolate); B = (1 + 3φ⁻²A)/(2φ⁻²(1+φ⁻²)).
  for (double phi : {0.05, 0.1, 0.5, 0.9, 1.1, 2.0, 5.0, 20.0}) {
    const double c = 1.0, a = phi;
    const SpheroidFactors f = spheroid_factors(a, c);
    const double q = 1.0 / (phi * phi);
    const double A = phi < 1 ? std::atan(std::sqrt(q - 1)) / std::sqrt(q - 1)
                             : std::log(phi + std::sqrt(phi * phi - 1)) / std::sqrt(1 - q);
    const double B = (1 + 3 * q * A) / (2 * q * (1 + q));
    EXPECT_NEAR(f.A / A, 1.0, 1e-9) << "phi=" << phi;
    EXPECT_NEAR(f.B / B, 1.0, 1e-9) << "phi=" << phi;
  }
}

TEST(HydroTheorySpheroid, FlatDiskLimitGivesBroadsideAndEdgewiseDiskFriction) {
  // Thin circular disk of radius c: broadside ξ = 16ηc → G = 8/(3π); edgewise ξ = 32ηc/3 →
  // H = 16/(9π) (Oberbeck 1876; Happel & Brenner §4-26).
  const double phi = 1e-4, c = 1.0;
  const SpheroidFactors f = spheroid_factors(phi * c, c);
  EXPECT_NEAR(f.t_ax / (8.0 / (3 * kPi)), 1.0, 1e-3);
  EXPECT_NEAR(f.t_perp / (16.0 / (9 * kPi)), 1.0, 1e-3);
}

TEST(HydroTheorySpheroid, TriaxialFrictionIsInvariantUnderRelabellingOfAxes) {
  const auto t = ellipsoid_translational_friction(1.0, 2.0, 3.5);
  const auto r = ellipsoid_rotational_friction(1.0, 2.0, 3.5);
  const auto tp = ellipsoid_translational_friction(3.5, 1.0, 2.0);  // (b3, b1, b2)
  const auto rp = ellipsoid_rotational_friction(3.5, 1.0, 2.0);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(tp[(i + 1) % 3] / t[i], 1.0, 1e-10);
    EXPECT_NEAR(rp[(i + 1) % 3] / r[i], 1.0, 1e-10);
  }
  // Larger cross-section ⇒ larger drag: motion along the longest axis is easiest.
  EXPECT_LT(t[2], t[1]);
  EXPECT_LT(t[1], t[0]);
}

// ---- capacitance ------------------------------------------------------------------------------------

TEST(HydroTheoryCapacitance, SpheroidClosedFormsMatchTheEllipsoidIntegralAndTheDiskLimit) {
  EXPECT_NEAR(spheroid_capacitance(1.3, 1.3), 1.3, 1e-15);
  EXPECT_NEAR(ellipsoid_capacitance(1.3, 1.3, 1.3) / 1.3, 1.0, 1e-10);
  for (double a : {0.05, 0.3, 0.9, 1.1, 3.0, 10.0}) {
    EXPECT_NEAR(spheroid_capacitance(a, 1.0) / ellipsoid_capacitance(1.0, 1.0, a), 1.0, 1e-10) << "a = " << a;
  }
  // Thin disk of radius c: C = 2c/π; needle of half-length a: C → a/ln(2a/c).
  EXPECT_NEAR(spheroid_capacitance(1e-9, 1.0) / (2.0 / kPi), 1.0, 1e-8);
  EXPECT_NEAR(spheroid_capacitance(1e6, 1.0) * std::log(2e6) / 1e6, 1.0, 1e-6);
}

TEST(HydroTheoryCapacitance, EllipsoidHydrodynamicRadiusEqualsItsCapacitance) {
  // R_h = 1/(6πη D̄_t), D̄_t the mean of the three translational mobilities (Perrin), equals 2/χ.
  for (const std::array<double, 3>& b : {std::array<double, 3>{1, 1, 1}, {0.5, 0.5, 3}, {2, 2, 0.2}, {0.5, 4, 6}}) {
    const auto d = ellipsoid_diffusion(b[0], b[1], b[2]);
    const double mean_mobility = (d.D_trans[0] + d.D_trans[1] + d.D_trans[2]) / 3.0;
    EXPECT_NEAR(1.0 / (6.0 * kPi * mean_mobility) / ellipsoid_capacitance(b[0], b[1], b[2]), 1.0, 1e-9);
  }
}

// ---- Tirado–García de la Torre cylinder table (spec 70 §6.2, k_BT = 1) ------------------------------

TEST(HydroTheoryCylinder, TiradoGarciaDeLaTorreTableOfSpec70Section6_2) {
  // Columns as printed: d, L, ηD_∥, ηD_⊥, ηD_t, ηD_r, D_∥/D_⊥, d̄_t, d̄_r.
  struct Row {
    double d, L;
    const char* par; const char* perp; const char* t; const char* r;
    const char* ratio; const char* dt; const char* dr;
  };
  const Row rows[] = {
      {1, 2, "0.07503", "0.06696", "0.06699", "0.056955", "1.121", "1.584", "1.775"},
      {1, 3, "0.06385", "0.05372", "0.05616", "0.026056", "1.189", "1.889", "2.303"},
      {1, 4, "0.05634", "0.04548", "0.04863", "0.014181", "1.239", "2.182", "2.821"},
      {1, 5, "0.05071", "0.03971", "0.04309", "0.008624", "1.277", "2.463", "3.330"},
      {1, 6, "0.04627", "0.03539", "0.03882", "0.005664", "1.308", "2.733", "3.830"},
      {2, 4, "0.03752", "0.03348", "0.03349", "0.007119", "1.121", "3.168", "3.549"},
      {2, 5, "0.03438", "0.02971", "0.03052", "0.004684", "1.157", "3.476", "4.081"},
      {2, 6, "0.03192", "0.02686", "0.02808", "0.003257", "1.189", "3.779", "4.606"},
      {3, 6, "0.02501", "0.02232", "0.02233", "0.002109", "1.121", "4.752", "5.324"},
  };
  const double eta = 2.5;  // η·D must not depend on η
  for (const Row& r : rows) {
    const CylinderDiffusion D = tirado_cylinder_diffusion(r.L, r.d, eta);
    SCOPED_TRACE("d = " + std::to_string(r.d) + ", L = " + std::to_string(r.L));
    EXPECT_TRUE(matches_printed(eta * D.D_par, r.par, 0)) << "eta D_par";
    EXPECT_TRUE(matches_printed(eta * D.D_perp, r.perp, 0)) << "eta D_perp";
    EXPECT_TRUE(matches_printed(eta * D.D_t, r.t, 0)) << "eta D_t";
    EXPECT_TRUE(matches_printed(eta * D.D_r, r.r, 0)) << "eta D_r";
    EXPECT_TRUE(matches_printed(D.D_par / D.D_perp, r.ratio, 0)) << "D_par/D_perp";
    // Stokes-equivalent diameters: d̄_t = L/(ln p + ν_t) = 1/(3πηD_t), d̄_r = (1/(πηD_r))^{1/3}.
    EXPECT_TRUE(matches_printed(1.0 / (3 * kPi * eta * D.D_t), r.dt, 0)) << "d_t";
    EXPECT_TRUE(matches_printed(std::cbrt(1.0 / (kPi * eta * D.D_r)), r.dr, 0)) << "d_r";
  }
}

TEST(HydroTheoryCylinder, AveragedFitDiffersFromMeanOfParallelAndPerpendicular) {
  // Spec 70 §6.2: for (d, L) = (1, 2), η(D_∥ + 2D_⊥)/3 = 0.06965 against ηD_t = 0.06699.
  const CylinderDiffusion D = tirado_cylinder_diffusion(2.0, 1.0);
  EXPECT_TRUE(matches_printed((D.D_par + 2 * D.D_perp) / 3, "0.06965", 0));
  EXPECT_TRUE(matches_printed(D.D_t, "0.06699", 0));
}

// Shell-model diffusion tensors against theory and published values (docs/validation.md, the
// hydro section, reports these numbers). Slow: about two minutes on one core.
//  - sphere: Stokes–Einstein and Stokes–Einstein–Debye within 0.5 %;
//  - the 16 constant-volume spheroids of spec 40 §5.3 (φ = 1/10 … 10): Perrin's exact
//    ellipsoid results (tests/support/hydro_theory.hpp) within 1 % (translation) and 2 %
//    (rotation) per body axis;
//  - cylinders p = 2 … 20 against Tirado–García de la Torre (TGdlT): the end-over-end D_r and the
//    orientational mean D_t within 3 %; D_∥ and D_⊥ are printed, and held within 5 %: at p ≤ 6 the
//    TGdlT fits for D_∥ and D_⊥ disagree with TGdlT's own D_t fit by up to 4 % (spec 70 §6.2), and
//    the shell model agrees with the D_t fit;
//  - boards 12×1×1, 12×8×1 and the unit cube: the published HYDRO++ values of spec 10 §8 are
//    printed with the deviation. They are not asserted (they differ by 4–29 %, see
//    docs/validation.md); the equal-area cylinder estimate of spec 10 §8.4 is held within 6 %.
#include <gtest/gtest.h>

#include <cstdio>

#include "anisodyn/hydro/diffusion_tensor.hpp"
#include "hydro_theory.hpp"

using namespace anisodyn;
using namespace anisodyn::hydro;

namespace {

DiffusionTensorResult solve(const HydroShape& s, std::size_t max_beads = 6000) {
  return compute_diffusion_tensor(s, choose_bead_radii(s, {5, max_beads, 2.0}));
}

double deviation(double got, double want) { return got / want - 1.0; }

}  // namespace

TEST(HydroValidation, SphereMatchesStokesEinsteinAndDebye) {
  const auto r = solve(HydroShape::sphere(1.0));
  for (int a = 0; a < 3; ++a) {
    EXPECT_LT(std::abs(deviation(r.D_trans()[a], theory::stokes_einstein_diffusion(0.5))), 0.005);
    EXPECT_LT(std::abs(deviation(r.D_rot()[a], theory::stokes_einstein_debye_rotational_diffusion(0.5))), 0.005);
  }
  std::printf("sphere d=1: D_t %.6f (SE %.6f)  D_r %.6f (SED %.6f)\n", r.D_trans().x(),
              theory::stokes_einstein_diffusion(0.5), r.D_rot().x(), theory::stokes_einstein_debye_rotational_diffusion(0.5));
}

TEST(HydroValidation, SpheroidsOfSpec40MatchPerrin) {
  const double phis[] = {1.0 / 10, 1.0 / 5, 1.0 / 4, 1.0 / 3, 1.0 / 2, 2.0 / 3, 4.0 / 5, 9.0 / 10,
                         10.0 / 9, 5.0 / 4, 3.0 / 2, 2.0, 3.0, 4.0, 5.0, 10.0};
  std::printf("%8s %9s %9s %9s %9s %9s %9s  (deviation from Perrin, %%)\n", "phi", "Dt_x", "Dt_y", "Dt_z", "Dr_x", "Dr_y", "Dr_z");
  for (double phi : phis) {
    const double a = std::pow(phi, 2.0 / 3.0), c = std::pow(phi, -1.0 / 3.0);  // a c² = 1
    // The rim of the φ = 1/10 disk has a curvature radius a²/c = 0.02: it needs finer shells.
    const auto r = solve(HydroShape::ellipsoid(Vec3(c, c, a)), phi < 0.15 ? 10000 : 6000);
    const auto exact = theory::ellipsoid_diffusion(c, c, a);
    std::printf("%8.4f", phi);
    for (int k = 0; k < 3; ++k) std::printf(" %+9.3f", 100 * deviation(r.D_trans()[k], exact.D_trans[static_cast<std::size_t>(k)]));
    for (int k = 0; k < 3; ++k) std::printf(" %+9.3f", 100 * deviation(r.D_rot()[k], exact.D_rot[static_cast<std::size_t>(k)]));
    std::printf("   extrapolation error estimate %.2f%%\n", 100 * r.relative_error.maxCoeff());
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT(std::abs(deviation(r.D_trans()[k], exact.D_trans[static_cast<std::size_t>(k)])), 0.01) << "phi " << phi << " axis " << k;
      EXPECT_LT(std::abs(deviation(r.D_rot()[k], exact.D_rot[static_cast<std::size_t>(k)])), 0.02) << "phi " << phi << " axis " << k;
    }
  }
}

TEST(HydroValidation, CylindersAgainstTiradoGarciaDeLaTorre) {
  std::printf("%5s %9s %9s %9s %9s  (deviation from TGdlT, %%)\n", "p", "D_par", "D_perp", "D_t", "D_r");
  for (double p : {2.0, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0, 15.0, 20.0}) {
    const auto r = solve(HydroShape::cylinder(p, 1.0));
    const auto tg = theory::tirado_cylinder_diffusion(p, 1.0);
    const double d_par = deviation(r.D_trans().z(), tg.D_par), d_perp = deviation(r.D_trans().x(), tg.D_perp);
    const double d_t = deviation(r.D_trans().mean(), tg.D_t), d_r = deviation(r.D_rot().x(), tg.D_r);
    std::printf("%5.0f %+9.3f %+9.3f %+9.3f %+9.3f\n", p, 100 * d_par, 100 * d_perp, 100 * d_t, 100 * d_r);
    EXPECT_LT(std::abs(d_t), 0.03) << p;
    EXPECT_LT(std::abs(d_r), 0.03) << p;
    EXPECT_LT(std::abs(d_par), 0.05) << p;
    EXPECT_LT(std::abs(d_perp), 0.05) << p;
  }
}

TEST(HydroValidation, BoardsAndCubeAgainstPublishedValues) {
  struct Case { const char* name; Vec3 edges; Vec3 Dt, Dr; };
  const Case cases[] = {{"board 1x1x12", Vec3(1, 1, 12), Vec3(2.2e-2, 2.2e-2, 3.1e-2), Vec3(1.1e-3, 1.1e-3, 2.3e-2)},
                        {"board 1x8x12", Vec3(1, 8, 12), Vec3(9.4e-3, 1.4e-2, 1.5e-2), Vec3(3.5e-4, 3.6e-4, 6.3e-4)},
                        {"cube", Vec3(1, 1, 1), Vec3::Constant(8.35e-2), Vec3::Constant(1.48e-1)}};
  for (const auto& c : cases) {
    const auto r = solve(HydroShape::cuboid(c.edges), 12000);
    std::printf("%-13s D_trans %.4g %.4g %.4g (published %+.1f%% %+.1f%% %+.1f%%)  D_rot %.4g %.4g %.4g (%+.1f%% %+.1f%% %+.1f%%)\n",
                c.name, r.D_trans().x(), r.D_trans().y(), r.D_trans().z(), 100 * deviation(r.D_trans().x(), c.Dt.x()),
                100 * deviation(r.D_trans().y(), c.Dt.y()), 100 * deviation(r.D_trans().z(), c.Dt.z()), r.D_rot().x(),
                r.D_rot().y(), r.D_rot().z(), 100 * deviation(r.D_rot().x(), c.Dr.x()), 100 * deviation(r.D_rot().y(), c.Dr.y()),
                100 * deviation(r.D_rot().z(), c.Dr.z()));
    EXPECT_LT(r.relative_error.maxCoeff(), 0.01) << c.name;
    if (c.edges.y() == 1.0 && c.edges.z() == 12.0) {
      // Spec 10 §8.4: TGdlT for the equal-area cylinder d = 2/√π, L = 12.
      const auto tg = theory::tirado_cylinder_diffusion(12.0, 2.0 / std::sqrt(M_PI));
      EXPECT_LT(std::abs(deviation(r.D_trans().z(), tg.D_par)), 0.06);
      EXPECT_LT(std::abs(deviation(r.D_trans().x(), tg.D_perp)), 0.06);
      EXPECT_LT(std::abs(deviation(r.D_rot().x(), tg.D_r)), 0.06);
    }
  }
}

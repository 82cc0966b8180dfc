// The two shell constructions against each other (docs/validation.md reports these numbers).
// "surface_grid" (the default: grid nodes, edges and corners included) and "cell_centres" (one bead
// per cell centre, none on an edge) share no placement rule. Both at 5 shells, σ_b over a factor 2,
// finest ≈ 6000 beads (sphere) or ≈ 12000 (cube, boards 1×1×12 and 1×8×12). Asserted:
//  - the translational diagonal of D, as the tool outputs it (linear extrapolation), agrees within
//    0.5 % for all four bodies, and the rotational diagonal for the sphere;
//  - every diagonal element, extrapolated quadratically instead, agrees within 0.5 %: the two
//    discretisations converge to the same body.
// Printed, not asserted: the linearly extrapolated rotational diagonal of the cuboids, where the two
// constructions differ by up to 0.84 % (the issue asked for 0.5 %: not met). Refining the shells
// (docs/validation.md, manifests/validation/hydro_shell_convergence.json) shows the two series
// approaching one limit from opposite sides, so the difference is the linear extrapolation's own
// error (about half of it in each construction), not a disagreement about the body.
// Slow: about 1.5 minutes of CPU time.
#include <gtest/gtest.h>

#include <cstdio>

#include "anisodyn/hydro/diffusion_tensor.hpp"

using namespace anisodyn;
using namespace anisodyn::hydro;

namespace {

constexpr double kAgreement = 0.005;

DiffusionTensorResult solve(const HydroShape& s, std::size_t max_beads, ShellConstruction construction) {
  return compute_diffusion_tensor(s, choose_bead_radii(s, {5, max_beads, 2.0}, construction), {}, nullptr, construction);
}

void print_deviations(const char* label, const Mat6& cells, const Mat6& grid) {
  std::printf("  %-9s", label);
  for (int i = 0; i < 6; ++i) std::printf(" %+.3f", 100 * (cells(i, i) / grid(i, i) - 1.0));
  std::printf("\n");
}

/// assert_linear_rotation: the sphere's rotational diagonal is held to the criterion as well.
void expect_constructions_agree(const char* name, const HydroShape& shape, std::size_t max_beads, bool assert_linear_rotation) {
  const auto grid = solve(shape, max_beads, &shell_beads);
  const auto cells = solve(shape, max_beads, &cell_centre_beads);
  std::printf("%s: cell_centres vs surface_grid, %% (D_t,x D_t,y D_t,z D_r,x D_r,y D_r,z); finest shells %zu, %zu beads;"
              " extrapolation error estimates %.2f%%, %.2f%%\n",
              name, grid.shells.back().beads, cells.shells.back().beads, 100 * grid.relative_error.maxCoeff(),
              100 * cells.relative_error.maxCoeff());
  print_deviations("linear", cells.diffusion, grid.diffusion);
  print_deviations("quadratic", cells.quadratic_diffusion, grid.quadratic_diffusion);
  for (int i = 0; i < 6; ++i) {
    if (i < 3 || assert_linear_rotation)
      EXPECT_LT(std::abs(cells.diffusion(i, i) / grid.diffusion(i, i) - 1.0), kAgreement) << name << " linear, diagonal " << i;
    EXPECT_LT(std::abs(cells.quadratic_diffusion(i, i) / grid.quadratic_diffusion(i, i) - 1.0), kAgreement)
        << name << " quadratic, diagonal " << i;
  }
}

}  // namespace

TEST(ShellConstructions, AgreeAfterExtrapolationForTheSphere) {
  expect_constructions_agree("sphere", HydroShape::sphere(1.0), 6000, true);
}

TEST(ShellConstructions, AgreeAfterExtrapolationForTheCube) {
  expect_constructions_agree("cube", HydroShape::cuboid(Vec3::Ones()), 12000, false);
}

TEST(ShellConstructions, AgreeAfterExtrapolationForTheBoards) {
  expect_constructions_agree("board 1x1x12", HydroShape::cuboid(Vec3(1.0, 1.0, 12.0)), 12000, false);
  expect_constructions_agree("board 1x8x12", HydroShape::cuboid(Vec3(1.0, 8.0, 12.0)), 12000, false);
}

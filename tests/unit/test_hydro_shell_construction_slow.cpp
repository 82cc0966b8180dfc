// The two shell constructions against each other (docs/validation.md reports these numbers).
// "surface_grid" (the default: grid nodes, edges and corners included) and "cell_centres" (one bead
// per cell centre, none on an edge) share no placement rule. Both at 5 shells, σ_b over a factor 2,
// finest ≈ 6000 beads (sphere) or ≈ 12000 (cube, boards 1×1×12 and 1×8×12). Asserted, within 0.5 %,
// on every diagonal element of D for all four bodies:
//  - the default output (kDefaultExtrapolation, "auto"): each construction picks its own fit by its
//    own error estimate, so the two may differ in the fit they report;
//  - `"extrapolation": "quadratic"`.
// Printed, not asserted: the linear fits (the cuboids' rotational diagonals differ by up to 0.84 %
// there, the linear extrapolation's own error: docs/validation.md), the cubic fits, and each
// construction's error estimate for both fits.
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

void print_error_estimates(const char* label, const DiffusionTensorResult& r) {
  for (auto order : {ExtrapolationOrder::Linear, ExtrapolationOrder::Quadratic}) {
    const Vec6 e = r.relative_error_of(order);
    std::printf("  %-12s %-9s error estimate (vs %s), %%:", label, extrapolation_name(order).c_str(),
                r.error_reference_of(order).c_str());
    for (int i = 0; i < 6; ++i) std::printf(" %.3f", 100 * e[i]);
    std::printf("\n");
  }
}

void expect_constructions_agree(const char* name, const HydroShape& shape, std::size_t max_beads) {
  const auto grid = solve(shape, max_beads, &shell_beads);
  const auto cells = solve(shape, max_beads, &cell_centre_beads);
  std::printf("%s: cell_centres vs surface_grid, %% (D_t,x D_t,y D_t,z D_r,x D_r,y D_r,z); finest shells %zu, %zu beads;"
              " default extrapolation %s: surface_grid chose %s, cell_centres %s\n",
              name, grid.shells.back().beads, cells.shells.back().beads, extrapolation_name(kDefaultExtrapolation).c_str(),
              extrapolation_name(grid.extrapolation).c_str(), extrapolation_name(cells.extrapolation).c_str());
  print_deviations("default", cells.diffusion, grid.diffusion);
  print_deviations("linear", cells.linear_diffusion, grid.linear_diffusion);
  print_deviations("quadratic", cells.quadratic_diffusion, grid.quadratic_diffusion);
  if (cells.cubic_diffusion && grid.cubic_diffusion) print_deviations("cubic", *cells.cubic_diffusion, *grid.cubic_diffusion);
  print_error_estimates("surface_grid", grid);
  print_error_estimates("cell_centres", cells);
  std::printf("  D (surface_grid, cell_centres) linear / quadratic / cubic:\n");
  for (int i = 0; i < 6; ++i)
    std::printf("    %d: %.7g %.7g / %.7g %.7g / %.7g %.7g\n", i, grid.linear_diffusion(i, i), cells.linear_diffusion(i, i),
                grid.quadratic_diffusion(i, i), cells.quadratic_diffusion(i, i),
                grid.cubic_diffusion ? (*grid.cubic_diffusion)(i, i) : 0.0,
                cells.cubic_diffusion ? (*cells.cubic_diffusion)(i, i) : 0.0);
  // The tool's output with either extrapolation: diffusion_of(order) is what it writes for that order.
  for (int i = 0; i < 6; ++i) {
    EXPECT_LT(std::abs(cells.diffusion_of(ExtrapolationOrder::Quadratic)(i, i) /
                           grid.diffusion_of(ExtrapolationOrder::Quadratic)(i, i) - 1.0),
              kAgreement)
        << name << " quadratic, diagonal " << i;
    EXPECT_LT(std::abs(cells.diffusion(i, i) / grid.diffusion(i, i) - 1.0), kAgreement) << name << " default, diagonal " << i;
  }
}

}  // namespace

TEST(ShellConstructions, AgreeAfterExtrapolationForTheSphere) {
  expect_constructions_agree("sphere", HydroShape::sphere(1.0), 6000);
}

TEST(ShellConstructions, AgreeAfterExtrapolationForTheCube) {
  expect_constructions_agree("cube", HydroShape::cuboid(Vec3::Ones()), 12000);
}

TEST(ShellConstructions, AgreeAfterExtrapolationForTheBoards) {
  expect_constructions_agree("board 1x1x12", HydroShape::cuboid(Vec3(1.0, 1.0, 12.0)), 12000);
  expect_constructions_agree("board 1x8x12", HydroShape::cuboid(Vec3(1.0, 8.0, 12.0)), 12000);
}

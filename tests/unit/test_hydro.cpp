// Bead-model hydrodynamics (engine/*/hydro): each piece against an independent reference.
//  - RPY pair mobility: the far-field Oseen limit, continuity at r = 2a, the self term at r = 0;
//  - the mirror-symmetry block solve against the plain dense solve of the same beads;
//  - the centre of diffusion and the change of reference point against a recomputation with the
//    beads shifted (brute force), and the symmetric coupling at the centre of diffusion;
//  - the extrapolated sphere against Stokes–Einstein and Stokes–Einstein–Debye (0.5 %), a prolate
//    spheroid against Perrin (1 % translation, 2 % rotation; tests/support/hydro_theory.hpp);
//  - each extrapolation fit recovers its own polynomial exactly; the chosen fit (linear or
//    quadratic, the `extrapolation` key) is the output and its error estimate compares with the
//    next higher fit;
//  - shells of both constructions lie on the surface they model; the cell-centre sphere also
//    matches Stokes–Einstein–Debye within 0.5 %; bad shell series are refused;
//  - species files round-trip through JSON and HDF5 and feed species definitions.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "anisodyn/core/error.hpp"
#include "anisodyn/hydro/diffusion_tensor.hpp"
#include "anisodyn/hydro/extrapolation.hpp"
#include "anisodyn/hydro/hydro_config.hpp"
#include "anisodyn/hydro/mirror_symmetry.hpp"
#include "anisodyn/hydro/rigid_body_resistance.hpp"
#include "anisodyn/hydro/rpy.hpp"
#include "anisodyn/hydro/shell_surface.hpp"
#include "anisodyn/tool/json_config.hpp"
#include "anisodyn/io/species_file.hpp"
#include "anisodyn/io/species_config.hpp"
#include "hydro_theory.hpp"
#include "scratch_dir.hpp"

using namespace anisodyn;
using namespace anisodyn::hydro;

namespace {

double relative_difference(double a, double b) { return std::abs(a - b) / std::abs(b); }

/// An irregular bead cluster with no mirror symmetry (random points on a lumpy surface).
std::vector<Vec3> irregular_beads(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  std::vector<Vec3> out;
  while (out.size() < n) {
    const Vec3 u = Vec3(g(rng), g(rng), g(rng)).normalized();
    const Vec3 p = Vec3(1.0 * u.x(), 1.6 * u.y(), 2.3 * u.z()) + Vec3(0.3, -0.2, 0.5) * (u.x() > 0 ? 1.0 : 0.0);
    bool far = true;
    for (const auto& q : out) far = far && (q - p).norm() > 0.25;
    if (far) out.push_back(p);
  }
  return out;
}

/// A shell at σ_b = 0.1: every bead on the surface, nearest-neighbour spacing ≈ 2σ_b (no bead is
/// isolated and none coincide).
void expect_beads_on_surface_about_2_sigma_apart(const HydroShape& s, const std::vector<Vec3>& beads) {
  ASSERT_GT(beads.size(), 50u);
  for (const auto& b : beads) ASSERT_TRUE(on_surface(s, b, 1e-9)) << b.transpose();
  for (std::size_t i = 0; i < beads.size(); i += 7) {
    double nearest = 1e9;
    for (std::size_t j = 0; j < beads.size(); ++j)
      if (j != i) nearest = std::min(nearest, (beads[i] - beads[j]).norm());
    EXPECT_GT(nearest, 0.02);
    EXPECT_LT(nearest, 0.4);
  }
}

}  // namespace

TEST(RpyMobility, FarFieldIsTheOseenTensor) {
  const Vec3 r(30.0, -40.0, 120.0);
  const Mat3 oseen = (Mat3::Identity() + r * r.transpose() / r.squaredNorm()) / (8.0 * M_PI * r.norm());
  EXPECT_LT((rpy_mobility(r, 0.1) - oseen).norm() / oseen.norm(), 1e-6);
}

TEST(RpyMobility, IsContinuousAtContactAndSelfAtZeroSeparation) {
  const double a = 0.3;
  const Vec3 dir = Vec3(1.0, 2.0, -0.5).normalized();
  const Mat3 inside = rpy_mobility(dir * (2.0 * a * (1.0 - 1e-12)), a);
  const Mat3 outside = rpy_mobility(dir * (2.0 * a * (1.0 + 1e-12)), a);
  EXPECT_LT((inside - outside).norm(), 1e-9);
  EXPECT_LT((rpy_mobility(Vec3::Zero(), a) - Mat3::Identity() / (6.0 * M_PI * a)).norm(), 1e-15);
}

TEST(RigidBodyResistance, SingleBeadIsAStokesSphereForTranslation) {
  const auto r = rigid_body_resistance({{Vec3::Zero()}, 0.5});
  EXPECT_NEAR(r.resistance(0, 0), 6.0 * M_PI * 0.5, 1e-12);
  EXPECT_NEAR(r.resistance(2, 2), 6.0 * M_PI * 0.5, 1e-12);
}

TEST(RigidBodyResistance, MirrorBlocksEqualTheFullDenseSolve) {
  // A cuboid shell (all three mirror planes, beads on the planes too) and a cylinder.
  for (const auto& shape : {HydroShape::cuboid(Vec3(1.0, 2.0, 3.0)), HydroShape::cylinder(3.0, 1.0)}) {
    const BeadModel model{shell_beads(shape, 0.12), 0.12};
    ResistanceOptions plain;
    plain.use_symmetry = false;
    const auto full = rigid_body_resistance(model, plain);
    const auto split = rigid_body_resistance(model);
    EXPECT_EQ(full.symmetry_order, 1);
    EXPECT_EQ(split.symmetry_order, 8);
    EXPECT_LT(split.largest_block, full.largest_block / 4);
    EXPECT_LT((split.resistance - full.resistance).norm() / full.resistance.norm(), 1e-10);
  }
}

TEST(RigidBodyResistance, PartialSymmetryGroupMatchesTheFullSolve) {
  // A cone-like stack: symmetric under x and y reflections only (group of order 4).
  std::vector<Vec3> beads;
  for (int k = 0; k < 6; ++k)
    for (int i = 0; i < 8; ++i) {
      const double rho = 0.4 + 0.15 * k, phi = 2.0 * M_PI * (i + 0.5 * (k % 2)) / 8.0;
      beads.emplace_back(rho * std::cos(phi), rho * std::sin(phi), 0.3 * k);
    }
  ResistanceOptions plain;
  plain.use_symmetry = false;
  const auto full = rigid_body_resistance({beads, 0.1}, plain);
  const auto split = rigid_body_resistance({beads, 0.1});
  EXPECT_EQ(split.symmetry_order, 4);
  EXPECT_LT((split.resistance - full.resistance).norm() / full.resistance.norm(), 1e-10);
}

TEST(CentreOfDiffusion, MovingTheReferencePointMatchesShiftedBeads) {
  const auto beads = irregular_beads(120, 7);
  const Mat6 D = rigid_body_resistance({beads, 0.1}).resistance.inverse();
  const Vec3 p(0.4, -0.7, 1.1);
  std::vector<Vec3> shifted;
  for (const auto& b : beads) shifted.push_back(b - p);
  const Mat6 D_shifted = rigid_body_resistance({shifted, 0.1}).resistance.inverse();
  EXPECT_LT((move_reference_point(D, p) - D_shifted).norm() / D.norm(), 1e-10);
}

TEST(CentreOfDiffusion, CouplingIsSymmetricThereAndASymmetricBodyIsRecovered) {
  const auto beads = irregular_beads(120, 11);
  const Mat6 D = rigid_body_resistance({beads, 0.1}).resistance.inverse();
  const Vec3 c = centre_of_diffusion(D);
  const Mat3 coupling = move_reference_point(D, c).topRightCorner<3, 3>();
  EXPECT_LT((coupling - coupling.transpose()).norm(), 1e-12 * D.norm());

  // A spheroid shell displaced by d has its centre of diffusion at d.
  const Vec3 d(0.3, -0.5, 0.8);
  std::vector<Vec3> moved;
  for (const auto& b : shell_beads(HydroShape::ellipsoid(Vec3(1.0, 1.0, 2.0)), 0.15)) moved.push_back(b + d);
  const Mat6 Dm = rigid_body_resistance({moved, 0.15}).resistance.inverse();
  EXPECT_LT((centre_of_diffusion(Dm) - d).norm(), 1e-9);
  EXPECT_LT(relative_coupling(move_reference_point(Dm, d)), 1e-9);
}

TEST(ShellSurface, BeadsLieOnTheSurfaceAndKeepTheMirrorSymmetry) {
  const std::vector<HydroShape> shapes{HydroShape::sphere(2.0), HydroShape::ellipsoid(Vec3(0.5, 1.0, 3.0)),
                                       HydroShape::cylinder(4.0, 1.0), HydroShape::spherocylinder(3.0, 1.0),
                                       HydroShape::cuboid(Vec3(1.0, 3.4641, 12.0)),
                                       HydroShape::sphere_union({Vec3(0, 0, -0.6), Vec3(0, 0, 0), Vec3(0, 0, 0.6)}, {0.5, 0.5, 0.5})};
  for (const auto& s : shapes) {
    const auto beads = shell_beads(s, 0.1);
    expect_beads_on_surface_about_2_sigma_apart(s, beads);
    if (s.kind != HydroShapeKind::Ellipsoid || s.semi_axes.x() == s.semi_axes.y())
      EXPECT_EQ(find_mirror_symmetry(beads, 1e-9).operations.size(), 8u);
  }
}

TEST(ShellSurface, CellCentreBeadsLieOnTheSurfaceOffTheEdgesAndKeepTheMirrorSymmetry) {
  const std::vector<HydroShape> shapes{HydroShape::sphere(2.0), HydroShape::ellipsoid(Vec3(0.5, 1.0, 3.0)),
                                       HydroShape::cylinder(4.0, 1.0), HydroShape::cuboid(Vec3(1.0, 3.4641, 12.0))};
  for (const auto& s : shapes) {
    const auto beads = cell_centre_beads(s, 0.1);
    expect_beads_on_surface_about_2_sigma_apart(s, beads);
    EXPECT_EQ(find_mirror_symmetry(beads, 1e-9).operations.size(), 8u);
  }
  // Cuboid cells: the nearest bead to an edge is half a cell (σ_b) from each face meeting there.
  const HydroShape cube = HydroShape::cuboid(Vec3::Ones());
  for (const auto& b : cell_centre_beads(cube, 0.125)) {
    const Vec3 gap = Vec3::Constant(0.5) - b.cwiseAbs();
    int on_faces = 0;
    double off_face = 1.0;
    for (int a = 0; a < 3; ++a) {
      if (gap[a] < 1e-12) ++on_faces;
      else off_face = std::min(off_face, gap[a]);
    }
    EXPECT_EQ(on_faces, 1) << b.transpose();
    EXPECT_GE(off_face, 0.125 - 1e-12) << b.transpose();  // cells are 0.25 wide: the first centre is 0.125 in
  }
  EXPECT_EQ(cell_centre_beads(cube, 0.125).size(), 6u * 16u);
  EXPECT_THROW(cell_centre_beads(HydroShape::spherocylinder(2.0, 1.0), 0.1), InputError);
}

TEST(DiffusionTensor, CellCentreSphereMatchesStokesEinsteinAndDebye) {
  const HydroShape s = HydroShape::sphere(1.0);
  const auto r = compute_diffusion_tensor(s, choose_bead_radii(s, {5, 3000, 2.0}, &cell_centre_beads), {}, nullptr,
                                          &cell_centre_beads);
  for (int a = 0; a < 3; ++a) {
    EXPECT_LT(relative_difference(r.D_trans()[a], theory::stokes_einstein_diffusion(0.5)), 0.005);
    EXPECT_LT(relative_difference(r.D_rot()[a], theory::stokes_einstein_debye_rotational_diffusion(0.5)), 0.005);
  }
}

TEST(DiffusionTensor, SphereMatchesStokesEinsteinAndDebyeWithinHalfAPercent) {
  const auto r = compute_diffusion_tensor(HydroShape::sphere(1.0), choose_bead_radii(HydroShape::sphere(1.0), {5, 3000, 2.0}));
  for (int a = 0; a < 3; ++a) {
    EXPECT_LT(relative_difference(r.D_trans()[a], theory::stokes_einstein_diffusion(0.5)), 0.005);
    EXPECT_LT(relative_difference(r.D_rot()[a], theory::stokes_einstein_debye_rotational_diffusion(0.5)), 0.005);
  }
  EXPECT_LT(r.relative_coupling, 1e-8);
  EXPECT_LT(r.relative_error.maxCoeff(), 0.005);
  // The shells converge towards the answer from below: friction falls with the bead radius.
  for (std::size_t k = 1; k < r.shells.size(); ++k) EXPECT_GT(r.shells[k].diffusion(0, 0), r.shells[k - 1].diffusion(0, 0));
}

TEST(DiffusionTensor, ProlateSpheroidMatchesPerrin) {
  const double phi = 3.0, a = std::pow(phi, 2.0 / 3.0), c = std::pow(phi, -1.0 / 3.0);
  const HydroShape s = HydroShape::ellipsoid(Vec3(c, c, a));
  const auto r = compute_diffusion_tensor(s, choose_bead_radii(s, {5, 3000, 2.0}));
  const auto exact = theory::ellipsoid_diffusion(c, c, a);
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT(relative_difference(r.D_trans()[k], exact.D_trans[static_cast<std::size_t>(k)]), 0.01) << k;
    EXPECT_LT(relative_difference(r.D_rot()[k], exact.D_rot[static_cast<std::size_t>(k)]), 0.02) << k;
  }
}

TEST(Extrapolation, RecoversALineAndNeedsThreeRadii) {
  const auto e = extrapolate_to_zero_size({0.1, 0.2, 0.3, 0.4}, {1.5, 2.0, 2.5, 3.0});
  EXPECT_NEAR(e.linear, 1.0, 1e-12);
  EXPECT_NEAR(e.slope, 5.0, 1e-12);
  EXPECT_NEAR(e.quadratic, 1.0, 1e-10);
  ASSERT_TRUE(e.cubic.has_value());
  EXPECT_NEAR(*e.cubic, 1.0, 1e-10);
  EXPECT_THROW(extrapolate_to_zero_size({0.1, 0.2, 0.2}, {1, 2, 2}), InputError);
}

TEST(Extrapolation, EachFitRecoversItsPolynomialAndTheCubicNeedsFourRadii) {
  // y = 1 + 2σ + 30σ² − 100σ³ at σ_b of the size of real shells (T/(2n)).
  const std::vector<double> sigma{0.0625, 0.05, 0.0416667, 0.0357143, 0.03125};
  std::vector<double> parabola, cubic;
  for (double x : sigma) {
    parabola.push_back(1 + 2 * x + 30 * x * x);
    cubic.push_back(1 + 2 * x + 30 * x * x - 100 * x * x * x);
  }
  const auto p = extrapolate_to_zero_size(sigma, parabola);
  EXPECT_NEAR(p.quadratic, 1.0, 1e-11);
  EXPECT_NEAR(*p.cubic, 1.0, 1e-10);
  EXPECT_GT(std::abs(p.linear - 1.0), 1e-3);  // a line cannot follow the curvature
  EXPECT_DOUBLE_EQ(p.intercept(ExtrapolationOrder::Linear), p.linear);
  EXPECT_DOUBLE_EQ(p.intercept(ExtrapolationOrder::Quadratic), p.quadratic);
  const auto c = extrapolate_to_zero_size(sigma, cubic);
  EXPECT_NEAR(*c.cubic, 1.0, 1e-10);
  EXPECT_GT(std::abs(c.quadratic - 1.0), 1e-6);
  const auto three = extrapolate_to_zero_size({0.1, 0.2, 0.3, 0.3}, {1, 2, 3, 3});
  EXPECT_FALSE(three.cubic.has_value());  // three distinct radii: no cubic
}

TEST(DiffusionTensor, TheChosenExtrapolationIsTheOutputAndItsErrorEstimateComparesWithTheNextFit) {
  const HydroShape s = HydroShape::sphere(1.0);
  const std::vector<double> radii = choose_bead_radii(s, {4, 1500, 2.0});
  const auto lin = compute_diffusion_tensor(s, radii, {}, nullptr, &shell_beads, ExtrapolationRule::Linear);
  const auto quad = compute_diffusion_tensor(s, radii, {}, nullptr, &shell_beads, ExtrapolationRule::Quadratic);
  EXPECT_EQ(lin.extrapolation, ExtrapolationOrder::Linear);
  EXPECT_EQ(quad.extrapolation, ExtrapolationOrder::Quadratic);
  ASSERT_TRUE(quad.cubic_diffusion.has_value());
  EXPECT_TRUE(lin.diffusion.isApprox(lin.linear_diffusion, 1e-14));
  EXPECT_TRUE(quad.diffusion.isApprox(quad.quadratic_diffusion, 1e-14));
  EXPECT_TRUE(lin.quadratic_diffusion.isApprox(quad.quadratic_diffusion, 1e-14));  // same shells, same fits
  EXPECT_EQ(lin.error_reference_of(ExtrapolationOrder::Linear), "quadratic");
  EXPECT_EQ(quad.error_reference_of(ExtrapolationOrder::Quadratic), "cubic");
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(lin.relative_error[i], std::abs(lin.quadratic_diffusion(i, i) / lin.linear_diffusion(i, i) - 1.0), 1e-14);
    EXPECT_NEAR(quad.relative_error[i], std::abs((*quad.cubic_diffusion)(i, i) / quad.quadratic_diffusion(i, i) - 1.0),
                1e-14);
  }
  // Three radii: no cubic, so the quadratic fit is checked against the line.
  const std::vector<double> three(radii.begin(), radii.begin() + 3);
  const auto q3 = compute_diffusion_tensor(s, three, {}, nullptr, &shell_beads, ExtrapolationRule::Quadratic);
  EXPECT_FALSE(q3.cubic_diffusion.has_value());
  EXPECT_EQ(q3.error_reference_of(ExtrapolationOrder::Quadratic), "linear");
  EXPECT_NEAR(q3.relative_error[0], std::abs(q3.linear_diffusion(0, 0) / q3.quadratic_diffusion(0, 0) - 1.0), 1e-14);
}

TEST(Extrapolation, AutoPicksTheFitWithTheSmallerErrorEstimateAndLinearOnATie) {
  EXPECT_EQ(kDefaultExtrapolation, ExtrapolationRule::Auto);
  EXPECT_EQ(extrapolation_name(ExtrapolationRule::Auto), "auto");
  EXPECT_EQ(choose_extrapolation(0.004, 0.001), ExtrapolationOrder::Quadratic);
  EXPECT_EQ(choose_extrapolation(0.007, 0.53), ExtrapolationOrder::Linear);
  EXPECT_EQ(choose_extrapolation(0.0012, 0.0012), ExtrapolationOrder::Linear);  // tie: the simpler fit
  EXPECT_EQ(choose_extrapolation(0.0012, std::nan("")), ExtrapolationOrder::Linear);
  EXPECT_EQ(choose_extrapolation(0.0012, std::numeric_limits<double>::infinity()), ExtrapolationOrder::Linear);
}

TEST(DiffusionTensor, AutoOutputsTheFitWhoseOwnErrorEstimateIsSmaller) {
  // Two bodies at coarse shells, one of which should go each way; whichever way each goes, the
  // output must be the fit with the smaller largest-diagonal estimate, with that fit's estimate.
  int chosen[2] = {0, 0};
  for (const HydroShape& s : {HydroShape::sphere(1.0), HydroShape::cuboid(Vec3(1.0, 1.0, 4.0)),
                              HydroShape::ellipsoid(Vec3(1.5, 1.5, 0.3)), HydroShape::ellipsoid(Vec3(1.0, 1.0, 2.0))}) {
    const auto a = compute_diffusion_tensor(s, choose_bead_radii(s, {4, 1200, 2.0}), {}, nullptr, &shell_beads,
                                            ExtrapolationRule::Auto);
    const double lin = a.relative_error_of(ExtrapolationOrder::Linear).maxCoeff();
    const double quad = a.relative_error_of(ExtrapolationOrder::Quadratic).maxCoeff();
    EXPECT_EQ(a.rule, ExtrapolationRule::Auto);
    EXPECT_EQ(a.extrapolation, quad < lin ? ExtrapolationOrder::Quadratic : ExtrapolationOrder::Linear);
    EXPECT_TRUE(a.diffusion.isApprox(a.diffusion_of(a.extrapolation), 1e-14));
    EXPECT_TRUE(a.relative_error.isApprox(a.relative_error_of(a.extrapolation), 1e-14));
    EXPECT_NEAR(a.relative_error.maxCoeff(), std::min(lin, quad), 1e-15);
    ++chosen[a.extrapolation == ExtrapolationOrder::Quadratic];
  }
  EXPECT_GT(chosen[0], 0) << "no body chose the line";
  EXPECT_GT(chosen[1], 0) << "no body chose the parabola";
}

TEST(HydroConfig, ExtrapolationKeyAtTopLevelAndPerSpecies) {
  const nlohmann::json sphere{{"type", "sphere"}, {"diameter", 1}};
  const nlohmann::json radii{0.1, 0.08, 0.06};
  {
    nlohmann::json j{{"species", {{{"name", "a"}, {"shape", sphere}, {"bead_radii", radii}}}}};
    tool::ConfigNode cfg(j, "h.json");
    EXPECT_EQ(parse_hydro_config(cfg).species[0].extrapolation, kDefaultExtrapolation);
  }
  {
    nlohmann::json j{{"extrapolation", "quadratic"},
                     {"species", {{{"name", "a"}, {"shape", sphere}, {"bead_radii", radii}},
                                  {{"name", "b"}, {"shape", sphere}, {"bead_radii", radii}, {"extrapolation", "linear"}}}}};
    tool::ConfigNode cfg(j, "h.json");
    const HydroConfig c = parse_hydro_config(cfg);
    EXPECT_EQ(c.species[0].extrapolation, ExtrapolationRule::Quadratic);
    EXPECT_EQ(c.species[1].extrapolation, ExtrapolationRule::Linear);
  }
  {
    nlohmann::json j{{"extrapolation", "linear"},
                     {"species", {{{"name", "a"}, {"shape", sphere}, {"bead_radii", radii}, {"extrapolation", "auto"}},
                                  {{"name", "b"}, {"shape", sphere}, {"bead_radii", radii}}}}};
    tool::ConfigNode cfg(j, "h.json");
    const HydroConfig c = parse_hydro_config(cfg);
    EXPECT_EQ(c.species[0].extrapolation, ExtrapolationRule::Auto);
    EXPECT_EQ(c.species[1].extrapolation, ExtrapolationRule::Linear);
  }
  nlohmann::json bad{{"extrapolation", "cubic"}, {"species", {{{"name", "a"}, {"shape", sphere}, {"bead_radii", radii}}}}};
  tool::ConfigNode cfg(bad, "h.json");
  EXPECT_THROW(parse_hydro_config(cfg), InputError);
  // A top-level default that every species overrides has no effect: refused.
  nlohmann::json unused{{"extrapolation", "quadratic"},
                        {"species", {{{"name", "a"}, {"shape", sphere}, {"bead_radii", radii}, {"extrapolation", "linear"}}}}};
  tool::ConfigNode cfg2(unused, "h.json");
  EXPECT_THROW(parse_hydro_config(cfg2), InputError);
}

TEST(ShellSeriesChoice, RefusesTooFewBeadsAndSnapsCuboidRadii) {
  const HydroShape board = HydroShape::cuboid(Vec3(1.0, 8.0, 12.0));
  EXPECT_THROW(choose_bead_radii(board, {5, 200, 2.0}), InputError);
  const auto radii = choose_bead_radii(board, {4, 12000, 2.0});
  ASSERT_EQ(radii.size(), 4u);
  for (double s : radii) EXPECT_NEAR(1.0 / (2.0 * s), std::round(1.0 / (2.0 * s)), 1e-9);  // σ_b = T/(2n)
  EXPECT_LE(radii.front(), 0.25);
}

class SpeciesFile : public anisodyn::testing_support::ScratchDirTest {
 protected:
  SpeciesFile() : ScratchDirTest("species-file") {}
  nlohmann::json document() const {
    return {{"format", "anisodyn-species"}, {"version", 1},
            {"species", {{{"name", "board_W1"}, {"shape", {{"type", "cuboid"}, {"edges", {1, 1, 12}}}},
                          {"D_trans", {0.02, 0.02, 0.03}}, {"D_rot", {0.001, 0.001, 0.02}}}}}};
  }
};

TEST_F(SpeciesFile, RoundTripsThroughJsonAndHdf5) {
  for (const std::string name : {"s.json", "s.h5"}) {
    io::write_species_file(file(name), document());
    EXPECT_EQ(io::read_species_file(file(name)), document()) << name;
  }
}

TEST_F(SpeciesFile, FeedsASpeciesDefinitionAndChecksItsShape) {
  io::write_species_file(file("s.h5"), document());
  const nlohmann::json good{{"name", "board"}, {"diffusion_from", {{"file", file("s.h5")}, {"species", "board_W1"}}}};
  const Species s = parse_species(tool::ConfigNode(good, "cfg.json"));
  EXPECT_EQ(s.shape.kind, ShapeKind::Cuboid);
  EXPECT_DOUBLE_EQ(s.shape.edges.z(), 12.0);
  EXPECT_DOUBLE_EQ(s.D_rot.z(), 0.02);

  nlohmann::json wrong_shape = good;
  wrong_shape["shape"] = {{"type", "cuboid"}, {"edges", {1, 8, 12}}};
  EXPECT_THROW(parse_species(tool::ConfigNode(wrong_shape, "cfg.json")), InputError);
  nlohmann::json missing = good;
  missing["diffusion_from"]["species"] = "board_W9";
  EXPECT_THROW(parse_species(tool::ConfigNode(missing, "cfg.json")), InputError);
  nlohmann::json both = good;
  both["D_trans"] = {1, 1, 1};
  EXPECT_THROW(parse_species(tool::ConfigNode(both, "cfg.json")), InputError);
}

// Shell-model diffusion tensors against exact references (docs/validation.md, the hydro section,
// reports these numbers). The sphere and spheroid references are asserted on the tool's default
// output (kDefaultExtrapolation, "auto": per body the fit with the smaller error estimate), the
// capacitance bound on the default and on both fits the tool offers (linear and quadratic, each
// with its own error estimate in δ); both fits are printed throughout. The quadratic fit alone
// fails the φ = 1/10 Perrin criteria at these shells (docs/decisions.md); auto picks the line there.
// Slow: about five minutes of CPU time.
//  - sphere: Stokes–Einstein and Stokes–Einstein–Debye within 0.5 %;
//  - the 16 constant-volume spheroids of spec 40 §5.3 (φ = 1/10 … 10): Perrin's exact ellipsoid
//    results (tests/support/hydro_theory.hpp) within 1 % (translation) and 2 % (rotation) per axis;
//  - the capacitance bound for every convex body: the sphere, the 16 spheroids, cylinders p = 2 … 20,
//    the cube and the boards L* = 12, W* ∈ {1, 2.5, 3, √12, 4, 6, 8, 12}. The hydrodynamic radius
//    R_h = 1/(6πη D̄_t), D̄_t the mean of the translational diagonal at the centre of diffusion, obeys
//    R_h ≥ C, C the electrostatic capacitance (Blawzdziewicz, Wajnryb, Given & Hubbard, Phys. Fluids
//    17, 033602 (2005)), and lies within a few per cent of it (Hubbard & Douglas, Phys. Rev. E 47,
//    R2983 (1993); for ellipsoids R_h = C exactly). Asserted: C(1 − δ) ≤ R_h ≤ 1.025 C, where δ is
//    only the stated numerical error, δ = e + 4 SE(C)/C + b(C):
//      e     the error anisodyn-hydro states for the body (the largest over the six diagonals of
//            its extrapolation-error estimate, DiffusionTensorResult::relative_error). The
//            translational diagonals' estimate alone is smaller than the known error of several
//            ellipsoids, so it would not bound the shell error;
//      SE(C) the walk-on-spheres standard error (4 SE, as for every statistical test here), 0 for
//            the closed-form ellipsoid capacitance;
//      b(C)  the bound on the walk's ε-shell bias, which can only raise C (walk_on_spheres.hpp).
//    Ellipsoids take the closed-form C; cylinders and cuboids the walk-on-spheres solver
//    (tests/support/walk_on_spheres.hpp), validated in tests/statistical/test_capacitance_walk*.cpp.
//  - printed, not asserted: the Tirado–García de la Torre cylinder fits and the published HYDRO++
//    values of spec 10 §8 for the boards W* = 1, 8 and the cube. They are not references: their
//    R_h falls below C, which no rigid body can do (the cube's by 3.8 %, the W* = 1 board's by
//    6.6 %, TGdlT's D_t fit by 1–1.9 % for every p ≥ 3, its (D_∥ + 2D_⊥)/3 for every p). The W* = 8
//    values respect the bound (R_h/C = 1.004) but come from the same unvalidated source, and the
//    bound tests only their mean.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <string>
#include <utility>

#include "anisodyn/hydro/diffusion_tensor.hpp"
#include "capacitance_bodies.hpp"
#include "hydro_theory.hpp"

using namespace anisodyn;
using namespace anisodyn::hydro;
using namespace anisodyn::testing_support;

namespace {

constexpr double kSigmas = 4.0;
constexpr double kWithinCapacitance = 0.025;  // R_h ≤ (1 + this) C
constexpr double kMaxRelativeSE = 2.5e-4;     // bound on SE(C)/C: a wide error bar cannot widen δ

/// Shell solutions, computed once per body and shared by the tests of this file.
const DiffusionTensorResult& solve(const std::string& name, const HydroShape& s, std::size_t max_beads) {
  static std::map<std::string, DiffusionTensorResult> cache;
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, compute_diffusion_tensor(s, choose_bead_radii(s, {5, max_beads, 2.0}))).first;
  return it->second;
}

double deviation(double got, double want) { return got / want - 1.0; }

double hydrodynamic_radius(double mean_translational_diffusion) { return 1.0 / (6.0 * M_PI * mean_translational_diffusion); }

const double kSpheroidPhis[] = {1.0 / 10, 1.0 / 5, 1.0 / 4, 1.0 / 3, 1.0 / 2, 2.0 / 3, 4.0 / 5, 9.0 / 10,
                                10.0 / 9, 5.0 / 4, 3.0 / 2, 2.0, 3.0, 4.0, 5.0, 10.0};

/// The spheroid of aspect ratio φ = a/c with a c² = 1 (symmetry semi-axis a along z).
Vec3 spheroid_semi_axes(double phi) {
  const double a = std::pow(phi, 2.0 / 3.0), c = std::pow(phi, -1.0 / 3.0);
  return Vec3(c, c, a);
}

const DiffusionTensorResult& spheroid_solution(double phi) {
  // The rim of the φ = 1/10 disk has a curvature radius a²/c = 0.02: it needs finer shells.
  return solve("spheroid " + std::to_string(phi), HydroShape::ellipsoid(spheroid_semi_axes(phi)), phi < 0.15 ? 10000 : 6000);
}

const double kCylinderAspects[] = {2.0, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0, 15.0, 20.0};

const DiffusionTensorResult& cylinder_solution(double p) {
  return solve("cylinder " + std::to_string(p), HydroShape::cylinder(p, 1.0), 6000);
}

const double kBoardWidths[] = {1.0, 2.5, 3.0, std::sqrt(12.0), 4.0, 6.0, 8.0, 12.0};

const DiffusionTensorResult& cuboid_solution(const Vec3& edges) {
  char name[64];
  std::snprintf(name, sizeof name, "cuboid %g %g %g", edges.x(), edges.y(), edges.z());
  return solve(name, HydroShape::cuboid(edges), 12000);
}

WalkOptions capacitance_walks(std::uint64_t seed) {
  WalkOptions o;
  o.walks = 400'000;
  o.pilot_walks = 40'000;
  o.seed = seed;
  return o;
}

struct Capacitance {
  double value, standard_error, bias_bound;
};

/// One row of the R_h/C table, for the default output and for either extrapolation the tool offers,
/// each with its own error estimate in δ (the default: the chosen fit's).
void check_bound(const std::string& name, const DiffusionTensorResult& r, const Capacitance& C) {
  EXPECT_LE(C.standard_error, kMaxRelativeSE * C.value) << name;
  const std::string chosen = "default=" + extrapolation_name(r.extrapolation);
  const std::pair<std::string, ExtrapolationOrder> rows[] = {{chosen, r.extrapolation},
                                                             {"linear", ExtrapolationOrder::Linear},
                                                             {"quadratic", ExtrapolationOrder::Quadratic}};
  for (const auto& [label, order] : rows) {
    const bool is_default = &label == &rows[0].first;
    const Mat6& D = is_default ? r.diffusion : r.diffusion_of(order);
    const double Rh = hydrodynamic_radius(D.diagonal().head<3>().mean());
    const Vec6 err = is_default ? r.relative_error : r.relative_error_of(order);
    const double e = err.maxCoeff();
    const double delta = e + kSigmas * C.standard_error / C.value + C.bias_bound;
    std::printf("%-22s %-17s R_h %.5f  C %.5f ± %.5f  R_h/C %.5f  delta %.3f%%  (shell error %.3f%%, translational %.3f%%)\n",
                name.c_str(), label.c_str(), Rh, C.value, C.standard_error, Rh / C.value, 100 * delta,
                100 * e, 100 * err.head<3>().maxCoeff());
    const std::string fit = name + " (" + label + ")";
    EXPECT_GE(Rh, C.value * (1.0 - delta)) << fit << ": R_h below the capacitance bound";
    EXPECT_LE(Rh, (1.0 + kWithinCapacitance) * C.value) << fit << ": R_h more than 2.5 % above C";
  }
}

Capacitance walk_capacitance(const ConvexBody& body, const LaunchEllipsoid& launch,
                             const std::vector<UnitChargePotential>& charges, std::uint64_t seed) {
  const auto c = walk_on_spheres_capacitance(body, launch, charges, capacitance_walks(seed));
  return {c.value, c.standard_error, c.bias_bound};
}

/// Computed once per cuboid, with a seed fixed by its edges.
const Capacitance& cuboid_capacitance(const Vec3& edges) {
  static std::map<std::vector<double>, Capacitance> cache;
  const std::vector<double> key{edges.x(), edges.y(), edges.z()};
  auto it = cache.find(key);
  if (it == cache.end()) {
    const CuboidBody body(edges);
    const auto seed = static_cast<std::uint64_t>(std::lround(1000 * edges.x() + 100 * edges.y() + edges.z()));
    it = cache.emplace(key, walk_capacitance(body, launch_for(body), cuboid_charges(body), seed)).first;
  }
  return it->second;
}

}  // namespace

TEST(HydroValidation, SphereMatchesStokesEinsteinAndDebye) {
  const auto& r = solve("sphere", HydroShape::sphere(1.0), 6000);
  const double Dt = theory::stokes_einstein_diffusion(0.5), Dr = theory::stokes_einstein_debye_rotational_diffusion(0.5);
  for (int a = 0; a < 3; ++a) {
    EXPECT_LT(std::abs(deviation(r.D_trans()[a], Dt)), 0.005);
    EXPECT_LT(std::abs(deviation(r.D_rot()[a], Dr)), 0.005);
  }
  std::printf("sphere d=1 default (auto) chose %s: D_t %+.3f%%, D_r %+.3f%% (worst axis)\n",
              extrapolation_name(r.extrapolation).c_str(),
              100 * (r.D_trans().array() / Dt - 1.0).abs().maxCoeff(), 100 * (r.D_rot().array() / Dr - 1.0).abs().maxCoeff());
  for (auto order : {ExtrapolationOrder::Linear, ExtrapolationOrder::Quadratic}) {
    const Mat6& D = r.diffusion_of(order);
    std::printf("sphere d=1 %-9s: D_t %.6f (SE %.6f, %+.3f%%)  D_r %.6f (SED %.6f, %+.3f%%)  error estimate %.3f%%\n",
                extrapolation_name(order).c_str(), D(0, 0), Dt, 100 * deviation(D(0, 0), Dt), D(3, 3), Dr,
                100 * deviation(D(3, 3), Dr), 100 * r.relative_error_of(order).maxCoeff());
  }
}

TEST(HydroValidation, SpheroidsOfSpec40MatchPerrin) {
  std::printf("%8s %-9s %9s %9s %9s %9s %9s %9s  (deviation from Perrin, %%)\n", "phi", "fit", "Dt_x", "Dt_y", "Dt_z", "Dr_x",
              "Dr_y", "Dr_z");
  for (double phi : kSpheroidPhis) {
    const Vec3 b = spheroid_semi_axes(phi);
    const auto& r = spheroid_solution(phi);
    const auto exact = theory::ellipsoid_diffusion(b.x(), b.y(), b.z());
    for (auto order : {ExtrapolationOrder::Linear, ExtrapolationOrder::Quadratic}) {
      const Mat6& D = r.diffusion_of(order);
      std::printf("%8.4f %-9s", phi, extrapolation_name(order).c_str());
      for (int k = 0; k < 3; ++k) std::printf(" %+9.3f", 100 * deviation(D(k, k), exact.D_trans[static_cast<std::size_t>(k)]));
      for (int k = 0; k < 3; ++k) std::printf(" %+9.3f", 100 * deviation(D(k + 3, k + 3), exact.D_rot[static_cast<std::size_t>(k)]));
      std::printf("   error estimate (vs %s) %.2f%%%s\n", r.error_reference_of(order).c_str(),
                  100 * r.relative_error_of(order).maxCoeff(), order == r.extrapolation ? "  <- default (auto)" : "");
    }
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT(std::abs(deviation(r.D_trans()[k], exact.D_trans[static_cast<std::size_t>(k)])), 0.01) << "phi " << phi << " axis " << k;
      EXPECT_LT(std::abs(deviation(r.D_rot()[k], exact.D_rot[static_cast<std::size_t>(k)])), 0.02) << "phi " << phi << " axis " << k;
    }
  }
}

TEST(HydroValidation, EllipsoidsRespectTheCapacitanceBound) {
  // For an ellipsoid R_h = C = 2/χ exactly, so these rows measure the shell model's own error.
  check_bound("sphere", solve("sphere", HydroShape::sphere(1.0), 6000), {0.5, 0.0, 0.0});
  for (double phi : kSpheroidPhis) {
    const Vec3 b = spheroid_semi_axes(phi);
    char name[32];
    std::snprintf(name, sizeof name, "spheroid phi %.4g", phi);
    check_bound(name, spheroid_solution(phi), {theory::spheroid_capacitance(b.z(), b.x()), 0.0, 0.0});
  }
}

TEST(HydroValidation, CylindersRespectTheCapacitanceBound) {
  std::uint64_t seed = 100;
  for (double p : kCylinderAspects) {
    const CylinderBody body(p, 1.0);
    const Capacitance C = walk_capacitance(body, launch_for(body), cylinder_charges(body), ++seed);
    char name[32];
    std::snprintf(name, sizeof name, "cylinder p %g", p);
    check_bound(name, cylinder_solution(p), C);
    // For information only: the TGdlT fits are not a reference, their R_h falls below C for p ≥ 3.
    const auto& r = cylinder_solution(p);
    const auto tg = theory::tirado_cylinder_diffusion(p, 1.0);
    std::printf("%22s TGdlT: R_h/C %.4f (D_t fit), %.4f ((D_par + 2 D_perp)/3); shell model vs TGdlT, %%: D_par %+.2f"
                " D_perp %+.2f D_t %+.2f D_r %+.2f\n", "",
                hydrodynamic_radius(tg.D_t) / C.value, hydrodynamic_radius((tg.D_par + 2 * tg.D_perp) / 3) / C.value,
                100 * deviation(r.D_trans().z(), tg.D_par), 100 * deviation(r.D_trans().x(), tg.D_perp),
                100 * deviation(r.D_trans().mean(), tg.D_t), 100 * deviation(r.D_rot().x(), tg.D_r));
  }
}

TEST(HydroValidation, CubeAndBoardsRespectTheCapacitanceBound) {
  check_bound("cube", cuboid_solution(Vec3::Ones()), cuboid_capacitance(Vec3::Ones()));
  for (double W : kBoardWidths) {
    const Vec3 edges(1.0, W, 12.0);
    char name[32];
    std::snprintf(name, sizeof name, "board W* %.4g", W);
    check_bound(name, cuboid_solution(edges), cuboid_capacitance(edges));
  }
}

TEST(HydroValidation, PublishedBoardAndCubeValuesForInformation) {
  // Spec 10 §8.1–8.2 (HYDRO++ values quoted by the thesis). Printed with their R_h/C, never
  // asserted: R_h/C < 1 breaks the rigorous bound R_h ≥ C, so these numbers cannot be a reference.
  struct Case { const char* name; Vec3 edges; Vec3 Dt, Dr; };
  const Case cases[] = {{"board 1x1x12", Vec3(1, 1, 12), Vec3(2.2e-2, 2.2e-2, 3.1e-2), Vec3(1.1e-3, 1.1e-3, 2.3e-2)},
                        {"board 1x8x12", Vec3(1, 8, 12), Vec3(9.4e-3, 1.4e-2, 1.5e-2), Vec3(3.5e-4, 3.6e-4, 6.3e-4)},
                        {"cube", Vec3(1, 1, 1), Vec3::Constant(8.35e-2), Vec3::Constant(1.48e-1)}};
  for (const auto& c : cases) {
    const auto& r = cuboid_solution(c.edges);
    const Capacitance& C = cuboid_capacitance(c.edges);
    std::printf("%-13s published R_h/C %.4f, shell model %.4f; D_trans %.6g %.6g %.6g (published %+.1f%% %+.1f%% %+.1f%%)"
                "  D_rot %.6g %.6g %.6g (%+.1f%% %+.1f%% %+.1f%%)\n",
                c.name, hydrodynamic_radius(c.Dt.mean()) / C.value, hydrodynamic_radius(r.D_trans().mean()) / C.value,
                r.D_trans().x(), r.D_trans().y(), r.D_trans().z(), 100 * deviation(r.D_trans().x(), c.Dt.x()),
                100 * deviation(r.D_trans().y(), c.Dt.y()), 100 * deviation(r.D_trans().z(), c.Dt.z()), r.D_rot().x(),
                r.D_rot().y(), r.D_rot().z(), 100 * deviation(r.D_rot().x(), c.Dr.x()), 100 * deviation(r.D_rot().y(), c.Dr.y()),
                100 * deviation(r.D_rot().z(), c.Dr.z()));
  }
}

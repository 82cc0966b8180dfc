// Raspberry construction (lb/raspberry.hpp) against independent references: the spheroid area
// against a quadrature of the surface of revolution, the bead counts and masses against spec 70's
// tables, the nearest surface point against a brute-force search over a fine (θ, φ) grid (spec 40
// §5.2's unit test), relaxed layers on their surfaces with even spacing, and the layers, fill and
// centre of a raspberry where spec 40 §5.1 puts them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "anisodyn/core/error.hpp"
#include "anisodyn/analysis/lb_analytic_checks.hpp"
#include "anisodyn/lb/raspberry.hpp"

using namespace anisodyn;
using namespace anisodyn::lb;

namespace {

/// Area of the spheroid x²/a² + (y² + z²)/c² = 1 as the surface of revolution of ρ(x) = c √(1 − x²/a²):
/// 2π ∫ ρ √(1 + ρ'²) dx, with x = a sin u (no endpoint singularity), midpoint rule on 20000 points.
double area_by_quadrature(double a, double c) {
  const int n = 20000;
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    const double u = -M_PI / 2 + (k + 0.5) * M_PI / n;
    // ρ = c cos u, dρ/dx = −(c/a) tan u, dx = a cos u du: ρ √(1 + ρ'²) dx = c cos u √(a² cos²u + c² sin²u) du.
    sum += c * std::cos(u) * std::sqrt(a * a * std::cos(u) * std::cos(u) + c * c * std::sin(u) * std::sin(u));
  }
  return 2.0 * M_PI * sum * M_PI / n;
}

Vec3 spheroid_axes(double phi) { return Vec3(4.25 * std::pow(phi, 2.0 / 3.0), 4.25 * std::pow(phi, -1.0 / 3.0), 4.25 * std::pow(phi, -1.0 / 3.0)); }

}  // namespace

TEST(Raspberry, SpheroidAreasMatchTheSurfaceOfRevolution) {
  for (double phi : {0.1, 0.25, 2.0 / 3.0, 1.0, 1.25, 3.0, 10.0}) {
    const Vec3 s = spheroid_axes(phi);
    EXPECT_NEAR(spheroid_area(s.x(), s.y()), area_by_quadrature(s.x(), s.y()), 1e-6 * area_by_quadrature(s.x(), s.y())) << phi;
  }
}

TEST(Raspberry, BeadCountsAndMassesMatchSpec70sTables) {
  // 70-theory.md §7.3: outer and inner beads of the sphere set, and the density-matched masses.
  const double radius[8] = {2.25, 2.75, 3.25, 3.75, 4.25, 4.75, 5.25, 5.75};
  const long outer[8] = {64, 95, 133, 177, 227, 284, 346, 415}, inner[8] = {38, 64, 95, 133, 177, 227, 284, 346};
  const double mass[8] = {286.5, 523.0, 863.3, 1326.2, 1930.6, 2695.3, 3639.2, 4781.2};
  for (int k = 0; k < 8; ++k) {
    EXPECT_EQ(std::lround(spheroid_area(radius[k], radius[k])), outer[k]) << radius[k];
    EXPECT_EQ(std::lround(spheroid_area(radius[k] - 0.5, radius[k] - 0.5)), inner[k]) << radius[k];
    EXPECT_NEAR(raspberry_mass(Vec3::Constant(radius[k]), 6.004), mass[k], 0.05) << radius[k];
  }
  // The spheroid set: φ → outer and inner beads.
  const double phi[6] = {0.1, 0.5, 0.9, 2.0, 5.0, 10.0};
  const long outer_s[6] = {543, 249, 227, 244, 310, 386}, inner_s[6] = {475, 196, 177, 191, 237, 280};
  for (int k = 0; k < 6; ++k) {
    const Vec3 s = spheroid_axes(phi[k]);
    EXPECT_EQ(std::lround(spheroid_area(s.x(), s.y())), outer_s[k]) << phi[k];
    EXPECT_EQ(std::lround(spheroid_area(s.x() - 0.5, s.y() - 0.5)), inner_s[k]) << phi[k];
  }
}

TEST(Raspberry, NearestSurfacePointMatchesABruteForceSearch) {
  // Points inside and outside oblate, prolate and triaxial ellipsoids: the bisection's point is on
  // the surface, and no point of a 1000 × 2000 (θ, φ) grid, refined around the best, is nearer.
  const Vec3 axes[3] = {spheroid_axes(0.25), spheroid_axes(4.0), Vec3(3.0, 2.0, 1.5)};
  const Vec3 points[5] = {Vec3(1.2, -0.7, 0.4), Vec3(5.0, 3.0, -2.0), Vec3(-0.3, 0.2, 2.9), Vec3(0.1, 4.4, 0.2), Vec3(9.0, -0.5, 0.3)};
  for (const Vec3& s : axes)
    for (const Vec3& r : points) {
      const analysis::checks::NearestPoint n = analysis::checks::nearest_point_against_brute_force(s, r);
      EXPECT_LT(n.off_surface, 1e-12);
      EXPECT_NEAR(n.bisection, n.brute_force, 1e-7) << s.transpose() << " / " << r.transpose();
      EXPECT_LT(n.point_difference, 1e-4) << s.transpose() << " / " << r.transpose();
    }
}

namespace {

/// Mean and coefficient of variation of each bead's distance to its nearest neighbour.
std::pair<double, double> nearest_neighbour_spacing(const std::vector<Vec3>& r) {
  std::vector<double> d(r.size(), std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < r.size(); ++i)
    for (std::size_t j = 0; j < r.size(); ++j)
      if (i != j) d[i] = std::min(d[i], (r[i] - r[j]).norm());
  double mean = 0.0, var = 0.0;
  for (double x : d) mean += x / static_cast<double>(d.size());
  for (double x : d) var += (x - mean) * (x - mean) / static_cast<double>(d.size() - 1);
  return {mean, std::sqrt(var) / mean};
}

}  // namespace

TEST(Raspberry, RelaxedLayersLieOnTheirSurfacesEvenlySpaced) {
  for (const Vec3& s : {Vec3(Vec3::Constant(4.25)), spheroid_axes(0.25), spheroid_axes(3.0)}) {
    const bool sphere = s.x() == s.y();
    const auto n = static_cast<std::size_t>(std::lround(spheroid_area(s.x(), s.y())));
    const std::vector<Vec3> layer = surface_layer(s, n, sphere ? sphere_layer_relaxation() : spheroid_layer_relaxation());
    ASSERT_EQ(layer.size(), n);
    double off = 0.0;
    for (const Vec3& r : layer) off = std::max(off, (r - nearest_surface_point(s, r)).norm());
    const auto [mean, cv] = nearest_neighbour_spacing(layer);
    std::printf("semi-axes (%.3f, %.3f, %.3f): %zu beads, largest distance from the surface %.2e nm, nearest-neighbour spacing %.4f nm, CV %.4f\n",
                s.x(), s.y(), s.z(), n, off, mean, cv);
    EXPECT_LT(off, 1e-9);
    EXPECT_LT(cv, 0.10);
    EXPECT_GT(mean, 0.9);  // 1 bead/nm² on a hexagonal net: 1.075 nm
  }
}

TEST(Raspberry, ARaspberryHasItsLayersFillAndCentre) {
  const Vec3 s = spheroid_axes(2.0);
  const RaspberryGeometry g = make_raspberry(s);
  EXPECT_EQ(static_cast<long>(g.count(BeadLayer::kOuter)), std::lround(spheroid_area(s.x(), s.y())));
  EXPECT_EQ(static_cast<long>(g.count(BeadLayer::kInner)), std::lround(spheroid_area(s.x() - 0.5, s.y() - 0.5)));
  EXPECT_EQ(g.count(BeadLayer::kCentre), 1u);
  EXPECT_GT(g.count(BeadLayer::kFill), 0u);
  const Vec3 fill = s - Vec3::Constant(1.0);
  for (std::size_t k = 0; k < g.offset.size(); ++k) {
    const Vec3& r = g.offset[k];
    switch (g.layer[k]) {
      case BeadLayer::kOuter: EXPECT_LT((r - nearest_surface_point(s, r)).norm(), 1e-9); break;
      case BeadLayer::kInner: EXPECT_LT((r - nearest_surface_point(s - Vec3::Constant(0.5), r)).norm(), 1e-9); break;
      case BeadLayer::kFill:
        EXPECT_LE(r.cwiseQuotient(fill).squaredNorm(), 1.0);
        EXPECT_EQ(r, r.array().round().matrix());  // on the 1 nm grid
        break;
      case BeadLayer::kCentre: EXPECT_EQ(r, Vec3::Zero()); break;
    }
  }
  EXPECT_EQ(g.layer[g.reference_bead], BeadLayer::kOuter);
  EXPECT_NEAR(g.reference_angle, std::acos(g.offset[g.reference_bead].x() / g.offset[g.reference_bead].norm()), 1e-15);
  EXPECT_THROW(make_raspberry(Vec3(0.4, 2.0, 2.0)), InputError);
  EXPECT_THROW(make_raspberry(Vec3(3.0, 2.0, 1.0)), InputError);  // triaxial
  // Mass and moments of the uniform spheroid.
  const double m = raspberry_mass(s, 6.004);
  const Vec3 moments = raspberry_moments(s, m);
  EXPECT_NEAR(moments.x(), m * 2.0 * s.y() * s.y() / 5.0, 1e-12 * moments.x());
  EXPECT_NEAR(moments.y(), m * (s.x() * s.x() + s.z() * s.z()) / 5.0, 1e-12 * moments.y());
}

TEST(Raspberry, TheSingleLayerAblationDropsTheOuterLayerOnly) {
  // Spec 40 §6's ablation: the same raspberry without its outer hydrodynamic-only layer; the
  // reference bead is then an inner-layer bead.
  const Vec3 s(4.25, 4.25, 4.25);
  const RaspberryGeometry two = make_raspberry(s), single = make_raspberry(s, false);
  EXPECT_EQ(single.count(BeadLayer::kOuter), 0u);
  EXPECT_EQ(single.count(BeadLayer::kInner), two.count(BeadLayer::kInner));
  EXPECT_EQ(single.count(BeadLayer::kFill), two.count(BeadLayer::kFill));
  EXPECT_EQ(single.count(BeadLayer::kCentre), 1u);
  EXPECT_EQ(single.offset.size(), two.offset.size() - two.count(BeadLayer::kOuter));
  EXPECT_EQ(single.layer[single.reference_bead], BeadLayer::kInner);
  EXPECT_NEAR(single.offset[single.reference_bead].norm(), 3.75, 1e-9);
}

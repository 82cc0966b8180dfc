// The walk-on-spheres capacitance solver (tests/support/walk_on_spheres.hpp, capacitance_bodies.hpp)
// against exact references: the sampling of the return point against its closed-form CDF and
// moments; the distances against brute force; the sphere, a prolate and an oblate spheroid against
// their closed-form capacitances; the cube against Hwang & Mascagni's C = 0.6606782 edge
// (J. Appl. Phys. 95, 3798 (2004)). Every estimate is held within k = 4 standard errors of its
// reference, and every standard error below a stated bound so that a wide error bar cannot pass.
// The cube to 10⁻⁴ is test_capacitance_walk_slow.cpp.
#include <gtest/gtest.h>

#include <cstdio>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "capacitance_bodies.hpp"
#include "thread_count.hpp"

using namespace anisodyn;
using namespace anisodyn::testing_support;

namespace {

constexpr double kSigmas = 4.0;
constexpr double kCube = 0.6606782;  // Hwang & Mascagni 2004, edge 1

void report(const char* name, const CapacitanceEstimate& c, double exact) {
  std::printf("%-22s C = %.7f ± %.7f (plain %.6f ± %.6f)  exact %.7f  dev %+.2f SE  launch C_B %.4f  hits %.3f  walks %llu\n",
              name, c.value, c.standard_error, c.plain_value, c.plain_standard_error, exact,
              (c.value - exact) / c.standard_error, c.launch_capacitance, double(c.hits) / double(c.walks),
              static_cast<unsigned long long>(c.walks));
}

/// |estimate − exact| ≤ k SE, and SE ≤ max_relative_se × exact.
void expect_within_error(double value, double se, double exact, double max_relative_se) {
  EXPECT_LE(std::abs(value - exact), kSigmas * se) << value << " vs " << exact << " (SE " << se << ")";
  EXPECT_LE(se, max_relative_se * exact);
}

WalkOptions walks(std::uint64_t n, std::uint64_t seed) {
  WalkOptions o;
  o.walks = n;
  o.pilot_walks = n / 10;
  o.seed = seed;
  return o;
}

/// Walks on a sphere need a return sphere larger than the body: the least one (the body itself)
/// would send every returning walker straight onto the surface.
WalkOptions sphere_walks(std::uint64_t n, std::uint64_t seed) {
  WalkOptions o = walks(n, seed);
  o.return_radius = 3.0;
  return o;
}

}  // namespace

TEST(CapacitanceWalk, ReturnCosineInvertsTheHarmonicMeasureCdf) {
  // CDF of ∝ (1 + q² − 2qu)^(−3/2): F(u) = (1 − q²)/(2q) [(1 + q² − 2qu)^(−1/2) − 1/(1 + q)].
  for (double q : {1e-9, 0.01, 0.3, 0.7, 0.99})
    for (double xi : {0.0, 1e-6, 0.1, 0.5, 0.9, 0.999999}) {
      const double u = wos_detail::return_cosine(q, xi);
      const double F = q < 1e-6 ? 0.5 * (u + 1.0)
                                : (1 - q * q) / (2 * q) * (1 / std::sqrt(1 + q * q - 2 * q * u) - 1 / (1 + q));
      EXPECT_NEAR(F, xi, 1e-9) << "q " << q << " xi " << xi;
    }
}

TEST(CapacitanceWalk, ReturnPointHasTheMomentsOfTheExteriorHarmonicMeasure) {
  // From x at distance r outside the sphere of radius R the return point Y has E[Y] = (R/r)² x (the
  // Kelvin image of x, since the linear functions are harmonic inside) and E[(Y·x̂)²] = R²(1 + 2q²)/3,
  // q = R/r (the harmonic polynomial 3(y·x̂)² − |y|²).
  const double R = 1.5;
  for (double r : {1.6, 3.0, 30.0}) {
    const Vec3 x = r * Vec3(1.0, -2.0, 0.5).normalized();
    const double q = R / r;
    Rng rng(11, static_cast<std::uint64_t>(r * 10));
    const int n = 200000;
    Vec3 sum = Vec3::Zero(), sum2 = Vec3::Zero();
    double axial2 = 0.0, axial4 = 0.0;
    for (int k = 0; k < n; ++k) {
      const Vec3 y = wos_detail::exterior_return_point(x, R, rng);
      ASSERT_NEAR(y.norm(), R, 1e-12);
      sum += y;
      sum2 += y.cwiseProduct(y);
      const double a = y.dot(x) / r;
      axial2 += a * a;
      axial4 += a * a * a * a;
    }
    const Vec3 mean = sum / n, se = ((sum2 / n - mean.cwiseProduct(mean)) / n).cwiseSqrt();
    const Vec3 image = q * q * x;
    for (int a = 0; a < 3; ++a) EXPECT_LE(std::abs(mean[a] - image[a]), kSigmas * se[a]) << "r " << r << " axis " << a;
    const double m2 = axial2 / n, se2 = std::sqrt((axial4 / n - m2 * m2) / n);
    EXPECT_LE(std::abs(m2 - R * R * (1 + 2 * q * q) / 3), kSigmas * se2) << "r " << r;
  }
}

TEST(CapacitanceWalk, DistancesAreExact) {
  // Ellipsoid: against a brute-force minimum over the surface (x = (e₁ sinθ cosφ, e₂ sinθ sinφ,
  // e₃ cosθ)) on a 200 × 400 grid, refined by successively finer local grids.
  const Vec3 e(0.7, 1.3, 2.9);
  auto surface = [&](double th, double ph) {
    return Vec3(e.x() * std::sin(th) * std::cos(ph), e.y() * std::sin(th) * std::sin(ph), e.z() * std::cos(th));
  };
  Rng rng(3, 0);
  for (int k = 0; k < 100; ++k) {
    const Vec3 y = (0.5 + 5.0 * rng.uniform()) * wos_detail::uniform_unit_vector(rng);
    const double d = ellipsoid_distance(e, y);
    if (y.cwiseQuotient(e).squaredNorm() <= 1.0) {
      EXPECT_EQ(d, 0.0);
      continue;
    }
    double best = 1e9, th0 = 0.0, ph0 = 0.0, dth = M_PI / 200, dph = 2 * M_PI / 400;
    for (int i = 0; i <= 200; ++i)
      for (int j = 0; j < 400; ++j)
        if (const double dist = (y - surface(i * dth, j * dph)).norm(); dist < best) best = dist, th0 = i * dth, ph0 = j * dph;
    for (int level = 0; level < 12; ++level) {
      const double cth = th0, cph = ph0;
      for (int i = -10; i <= 10; ++i)
        for (int j = -10; j <= 10; ++j)
          if (const double dist = (y - surface(cth + i * dth / 10, cph + j * dph / 10)).norm(); dist < best)
            best = dist, th0 = cth + i * dth / 10, ph0 = cph + j * dph / 10;
      dth /= 5, dph /= 5;
    }
    EXPECT_LE(d, best + 1e-12);
    EXPECT_NEAR(d, best, 1e-9) << y.transpose();
  }
  // Cuboid and cylinder: never farther than a dense sample of surface points, and within its spacing.
  const CuboidBody box(Vec3(1.0, 2.0, 3.0));
  const CylinderBody cyl(3.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    const Vec3 y = (2.0 + 3.0 * rng.uniform()) * wos_detail::uniform_unit_vector(rng);
    double box_min = 1e9, cyl_min = 1e9;
    for (int i = 0; i <= 60; ++i)
      for (int j = 0; j <= 60; ++j) {
        const double u = i / 60.0, v = j / 60.0;
        for (int face = 0; face < 6; ++face) {
          const int a = face / 2, b = (a + 1) % 3, c = (a + 2) % 3;
          Vec3 p;
          p[a] = (face % 2 ? 0.5 : -0.5) * Vec3(1, 2, 3)[a];
          p[b] = (u - 0.5) * Vec3(1, 2, 3)[b];
          p[c] = (v - 0.5) * Vec3(1, 2, 3)[c];
          box_min = std::min(box_min, (y - p).norm());
        }
        const double phi = 2 * M_PI * u;
        cyl_min = std::min(cyl_min, (y - Vec3(0.5 * std::cos(phi), 0.5 * std::sin(phi), 3.0 * (v - 0.5))).norm());
        for (double z : {-1.5, 1.5}) cyl_min = std::min(cyl_min, (y - Vec3(0.5 * v * std::cos(phi), 0.5 * v * std::sin(phi), z)).norm());
      }
    EXPECT_LE(box.distance(y), box_min + 1e-12);
    EXPECT_GT(box.distance(y), box_min - 0.05);
    EXPECT_LE(cyl.distance(y), cyl_min + 1e-12);
    EXPECT_GT(cyl.distance(y), cyl_min - 0.05);
  }
}

TEST(CapacitanceWalk, SphereWithAndWithoutTheCentreCharge) {
  const EllipsoidBody sphere(Vec3::Constant(1.0));
  const LaunchEllipsoid launch(Vec3::Constant(2.0));
  const auto plain = walk_on_spheres_capacitance(sphere, launch, {}, sphere_walks(200000, 5));
  report("sphere (plain)", plain, 1.0);
  expect_within_error(plain.value, plain.standard_error, 1.0, 3e-3);
  // With the centre charge the residual 1 − β/|X| is O(ε) at every hit: C is exact to ~ε.
  const auto cv = walk_on_spheres_capacitance(sphere, launch, {mirror_point_charges(Vec3::Zero())}, sphere_walks(20000, 6));
  report("sphere (centre charge)", cv, 1.0);
  EXPECT_LE(std::abs(cv.value - 1.0), kSigmas * cv.standard_error + cv.bias_bound);
  EXPECT_LT(cv.standard_error, 1e-6);
}

TEST(CapacitanceWalk, EpsilonShellBiasStaysWithinItsBound) {
  // Stopping at ε = 0.05 r_in: the estimate must lie in [C, (1 + 0.05)C] up to its error, and the
  // control-variate estimate (exact up to the ε-shell for a sphere) shows the bias itself.
  const EllipsoidBody sphere(Vec3::Constant(1.0));
  WalkOptions o = sphere_walks(200000, 7);
  o.epsilon = 0.05;
  const auto c = walk_on_spheres_capacitance(sphere, LaunchEllipsoid(Vec3::Constant(2.0)), {mirror_point_charges(Vec3::Zero())}, o);
  std::printf("sphere, eps = 0.05: C = %.6f ± %.6f, plain %.6f ± %.6f\n", c.value, c.standard_error, c.plain_value, c.plain_standard_error);
  EXPECT_GE(c.value, 1.0 - kSigmas * c.standard_error);
  EXPECT_LE(c.value, 1.0 + c.bias_bound + kSigmas * c.standard_error);
  EXPECT_GE(c.plain_value, 1.0 - kSigmas * c.plain_standard_error);
  EXPECT_LE(c.plain_value, 1.0 + c.bias_bound + kSigmas * c.plain_standard_error);
}

TEST(CapacitanceWalk, SpheroidsMatchTheirClosedForms) {
  struct Case { const char* name; Vec3 semi; Vec3 launch; };
  const Case cases[] = {{"prolate 1:1:3", Vec3(1, 1, 3), Vec3(1.5, 1.5, 3.3)},   // launch not a sphere
                        {"oblate 2:2:0.5", Vec3(2, 2, 0.5), Vec3::Constant(2.0)}};
  std::uint64_t seed = 20;
  for (const auto& c : cases) {
    const EllipsoidBody body(c.semi);
    const double exact = theory::spheroid_capacitance(c.semi.z(), c.semi.x());
    const auto est = walk_on_spheres_capacitance(body, LaunchEllipsoid(c.launch), spheroid_charges(body), walks(100000, ++seed));
    report(c.name, est, exact);
    expect_within_error(est.value, est.standard_error, exact, 2e-4);
    expect_within_error(est.plain_value, est.plain_standard_error, exact, 3e-3);
  }
}

TEST(CapacitanceWalk, CubeMatchesHwangMascagniFromTwoLaunchEllipsoids) {
  const CuboidBody cube(Vec3::Ones());
  const auto charges = cuboid_charges(cube);
  const auto best = walk_on_spheres_capacitance(cube, launch_for(cube), charges, walks(200000, 31));
  report("cube", best, kCube);
  expect_within_error(best.value, best.standard_error, kCube, 2e-4);
  expect_within_error(best.plain_value, best.plain_standard_error, kCube, 2e-3);
  // An elongated launch ellipsoid through the corners gives the same C.
  const auto other = walk_on_spheres_capacitance(cube, LaunchEllipsoid(Vec3(0.75, 0.75, 1.5)), charges, walks(200000, 32));
  report("cube (other launch)", other, kCube);
  expect_within_error(other.value, other.standard_error, kCube, 2e-4);
}

TEST(CapacitanceWalk, ResultDoesNotDependOnTheThreadCount) {
#ifdef _OPENMP
  const CylinderBody cyl(4.0, 1.0);
  const auto capacitance = [&] { return walk_on_spheres_capacitance(cyl, launch_for(cyl), cylinder_charges(cyl), walks(20000, 41)); };
  const auto one = with_threads(1, capacitance);
  const auto many = with_threads(std::max(2, omp_get_max_threads()), capacitance);
  EXPECT_EQ(one.value, many.value);
  EXPECT_EQ(one.hits, many.hits);
#else
  GTEST_SKIP() << "built without OpenMP";
#endif
}

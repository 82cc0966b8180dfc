// Collective rotational diffusion from the order tensor (spec 20 §7, spec 50 I3) on order-tensor
// series with a known rate. N independent rods take random walks on the sphere in which every step
// turns û by a fixed angle θ towards a uniformly random direction ⊥ û; by the addition theorem of
// the Legendre polynomials E[P_2(û'·n̂) | û] = P_2(cos θ) P_2(û·n̂) exactly, so
//   E[δS_zz(k)] = (2/3) P_2(cos θ)^k from the aligned start, and
//   C(k) = ⟨δS(k):δS(0)⟩ = (2/(3N)) P_2(cos θ)^k at equilibrium (cross terms of different rods vanish),
// i.e. both relax at 6 D with D = −ln P_2(cos θ)/(6h) exactly, whatever the step h (spec 20 §8.4–8.5).
// Also: the fit-window rules on a noiseless decay with noise and a spike, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "anisodyn/analysis/order_relaxation.hpp"
#include "anisodyn/core/error.hpp"
#include "input_error.hpp"
#include "scratch_dir.hpp"
#include "synthetic_trajectory.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;
using anisodyn::testing_support::input_error;
using anisodyn::testing_support::SyntheticTrajectory;

namespace {

constexpr double kStep = 0.01;  // time between order-tensor rows

/// θ of the steps for a rate D: P_2(cos θ) = exp(−6 D h).
double step_angle(double D) { return std::acos(std::sqrt((2.0 * std::exp(-6.0 * D * kStep) + 1.0) / 3.0)); }

Vec3 random_direction(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  return Vec3(g(rng), g(rng), g(rng)).normalized();
}

/// û turned by θ towards a uniformly random direction perpendicular to it.
Vec3 turn(const Vec3& u, double theta, std::mt19937_64& rng) {
  Vec3 w = random_direction(rng);
  w = (w - w.dot(u) * u).normalized();
  return (std::cos(theta) * u + std::sin(theta) * w).normalized();
}

/// The order-tensor rows (xx, yy, zz, xy, xz, yz) of n rods over `rows` rows, one step per row.
std::vector<std::pair<double, std::vector<double>>> rod_order_series(std::size_t n, std::size_t rows, double D, bool aligned, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::vector<Vec3> u(n, Vec3::UnitZ());
  if (!aligned)
    for (auto& v : u) v = random_direction(rng);
  const double theta = step_angle(D);
  std::vector<std::pair<double, std::vector<double>>> out;
  for (std::size_t k = 0; k < rows; ++k) {
    if (k > 0)
      for (auto& v : u) v = turn(v, theta, rng);
    Mat3 s = Mat3::Zero();
    for (const auto& v : u) s += v * v.transpose() / static_cast<double>(n);
    out.push_back({static_cast<double>(k) * kStep, {s(0, 0), s(1, 1), s(2, 2), s(0, 1), s(0, 2), s(1, 2)}});
  }
  return out;
}

SyntheticTrajectory carrier(const std::vector<std::pair<double, std::vector<double>>>& rows) {
  SyntheticTrajectory t;
  t.table = {Species{"rod", Shape::spherocylinder(5.0, 0.1), 1.0, Vec3(1, 1, 2), Vec3(0.5, 0.5, 0.0)}};
  t.time = {0.0, 1.0};
  t.position.assign(2, std::vector<Vec3>{Vec3(1, 1, 1)});
  t.observables.push_back({"order_tensor_rod", rows});
  return t;
}

class OrderRelaxationTest : public anisodyn::testing_support::ScratchDirTest {
 protected:
  OrderRelaxationTest() : ScratchDirTest("order-relaxation") {}

  std::vector<std::string> write(const std::vector<std::vector<std::pair<double, std::vector<double>>>>& replicas) {
    std::vector<std::string> paths;
    for (std::size_t r = 0; r < replicas.size(); ++r) {
      paths.push_back(file("rep" + std::to_string(r) + ".h5"));
      carrier(replicas[r]).write(paths.back());
    }
    return paths;
  }

  static OrderRelaxationAnalysis analyse(const OrderRelaxationSettings& s, const std::vector<std::string>& paths) {
    OrderRelaxationAnalysis a(s, paths.size(), "config.json");
    TrajectoryNeeds needs;
    needs.observables = {"order_tensor_rod"};
    for_each_replica(paths, needs, [&](const Trajectory& t, std::size_t) { a.accumulate(t, 0); });
    return a;
  }
};

OrderRelaxationSettings settings(const std::string& method, nlohmann::json extra = nlohmann::json::object()) {
  extra["method"] = method;
  tool::ConfigNode cfg(extra, "config.json");
  auto s = parse_order_relaxation_settings(cfg);
  cfg.finish();
  return s;
}

}  // namespace

TEST_F(OrderRelaxationTest, DecayOfAlignedFreeRodsGivesTheirRate) {
  constexpr double D = 0.5;
  std::vector<std::vector<std::pair<double, std::vector<double>>>> reps;
  for (unsigned r = 0; r < 16; ++r) reps.push_back(rod_order_series(1000, 300, D, true, 100 + r));
  const OrderDecayResult res = analyse(settings("decay"), write(reps)).decay();
  // The equilibrium noise of the mean of 16 decays is √(4/(45 N))/√16 = 0.0024 for N = 1000 (spec 20
  // §8.4); measured on the last quarter (about 2 correlation times) it is itself uncertain. 3× it
  // is below the band's 0.02, so the window is the band.
  const double expected_noise = std::sqrt(4.0 / (45.0 * 1000)) / 4.0;
  EXPECT_GT(res.noise, 0.3 * expected_noise);
  EXPECT_LT(res.noise, 2.5 * expected_noise);
  EXPECT_DOUBLE_EQ(res.threshold, 0.02);
  ASSERT_GE(res.fit.window.size(), 20u);
  // The window rule: from the first row below 0.1 to the last before the first at or below 0.02.
  EXPECT_LT(res.ds_zz[res.fit.window.first], 0.1);
  for (std::size_t k = 0; k < res.fit.window.first; ++k) EXPECT_GE(res.ds_zz[k], 0.1);
  for (std::size_t k = res.fit.window.first; k < res.fit.window.last; ++k) EXPECT_GT(res.ds_zz[k], 0.02);
  EXPECT_LE(res.ds_zz[res.fit.window.last], 0.02);
  // The generator itself: all rods start on ẑ, and after one step cos²θ − 1/3 = (2/3) P_2(cos θ).
  EXPECT_NEAR(res.ds_zz[0], 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(res.ds_zz[1], 2.0 / 3.0 * std::exp(-6 * D * kStep), 1e-12);
  ASSERT_TRUE(std::isfinite(res.fit.rate.error));
  EXPECT_LT(res.fit.rate.error, 0.1 * D);
  EXPECT_NEAR(res.fit.rate.value, D, 4 * res.fit.rate.error) << "D_r^coll " << res.fit.rate.value << " ± " << res.fit.rate.error;
  std::printf("decay: D_r^coll = %.5f ± %.5f (exact %.3f), window t = [%.3f, %.3f] (%zu rows), noise %.5f\n", res.fit.rate.value,
              res.fit.rate.error, D, res.fit.t_min, res.fit.t_max, res.fit.window.size(), res.noise);
}

TEST_F(OrderRelaxationTest, RegressionOfEquilibriumFreeRodsGivesTheirRate) {
  constexpr double D = 5.0 / 3.0;  // 6 D h = 0.1: a correlation time of 10 rows
  std::vector<std::vector<std::pair<double, std::vector<double>>>> reps;
  for (unsigned r = 0; r < 4; ++r) reps.push_back(rod_order_series(50, 40000, D, false, 200 + r));
  const OrderRegressionResult res = analyse(settings("regression"), write(reps)).regression();
  // C(0) = ⟨δS:δS⟩ of independent isotropic rods: (1/N)(⟨(û·û)²⟩ − 1/3) = 2/(3N).
  EXPECT_NEAR(res.correlation[0], 2.0 / (3.0 * 50), 4 * res.correlation_error[0]);
  ASSERT_GE(res.fit.window.size(), 6u);
  // The window rule on the lag grid: from the first lag at or below 0.5 to the last before the
  // first below 0.05.
  const std::size_t first = res.fit.window.first, last = res.fit.window.last;
  EXPECT_GT(res.normalised[first - 1], 0.5);
  EXPECT_LE(res.normalised[first], 0.5);
  for (std::size_t k = first; k < last; ++k) EXPECT_GE(res.normalised[k], 0.05);
  EXPECT_LT(res.normalised[last], 0.05);
  EXPECT_NEAR(res.fit.t_min, -std::log(0.5) / (6 * D), 2 * kStep);
  // Subtracting each run's own mean lowers C by about 2τ C(0)/T (τ = 1/(6D), T = 400): 0.1% of C(0),
  // a bias of the slope of ~0.5%, well inside the errors below.
  EXPECT_LT(res.fit.rate.error, 0.05 * D);
  EXPECT_NEAR(res.fit.rate.value, D, 4 * res.fit.rate.error) << "D_r^coll " << res.fit.rate.value << " ± " << res.fit.rate.error;
  std::printf("regression, 4 replicas: D_r^coll = %.5f ± %.5f (exact %.5f), window t = [%.3f, %.3f]\n", res.fit.rate.value,
              res.fit.rate.error, D, res.fit.t_min, res.fit.t_max);
  // One replica: 10 blocks of time origins stand in for replicas.
  const OrderRegressionResult one = analyse(settings("regression"), write({reps[0]})).regression();
  EXPECT_EQ(one.samples, 10u);
  EXPECT_NEAR(one.fit.rate.value, D, 4 * one.fit.rate.error) << "D_r^coll " << one.fit.rate.value << " ± " << one.fit.rate.error;
  std::printf("regression, 1 replica (blocks): D_r^coll = %.5f ± %.5f\n", one.fit.rate.value, one.fit.rate.error);
}

TEST_F(OrderRelaxationTest, DecayWindowStopsAtTheNoiseAndSkipsALaterSpike) {
  // δS_zz = 0.6 e^{−t} on rows t = 0.05 k, then ±0.01 of noise from t = 7.5 on (rms 0.01: the lower
  // edge becomes 3 × 0.01 = 0.03) and a spike of 0.05 at t = 6, back inside the band.
  std::vector<std::pair<double, std::vector<double>>> rows;
  for (std::size_t k = 0; k < 200; ++k) {
    const double t = 0.05 * static_cast<double>(k);
    double d = 0.6 * std::exp(-t);
    if (k >= 150) d += (k % 2 ? 0.01 : -0.01);
    if (k == 120) d = 0.05;
    rows.push_back({t, {(2.0 / 3.0 - d) / 2, (2.0 / 3.0 - d) / 2, 1.0 / 3.0 + d, 0, 0, 0}});
  }
  const OrderDecayResult res = analyse(settings("decay"), write({rows, rows})).decay();
  EXPECT_NEAR(res.noise, 0.01, 2e-4);
  EXPECT_NEAR(res.threshold, 3 * res.noise, 1e-15);
  // First row below 0.1: t > ln 6 = 1.79 → t = 1.80; last row above the edge ≈ 0.030: t < ln 20 ≈ 3.00.
  EXPECT_NEAR(res.fit.t_min, 1.80, 1e-9);
  EXPECT_NEAR(res.fit.t_max, 2.95, 1e-9);
  EXPECT_NEAR(res.fit.rate.value, 1.0 / 6.0, 1e-12);  // the noiseless decay rate, e^{−t} = e^{−6 (1/6) t}
  EXPECT_EQ(res.fit.rate.error, 0.0);                   // identical replicas
  // A band with no noise bound (factor small): the window runs down to 0.02 but still stops before the spike.
  const OrderDecayResult wide = analyse(settings("decay", {{"noise_factor", 0.1}}), write({rows, rows})).decay();
  EXPECT_NEAR(wide.fit.t_max, 3.40, 1e-9);  // 0.6 e^{−3.40} = 0.0200 > 0.02, 0.6 e^{−3.45} = 0.019
  EXPECT_LT(wide.fit.window.last, 120u);
}

TEST(OrderRelaxationSettings, KeysOfTheOtherMethodAndBadValuesAreInputErrors) {
  auto fails = [](nlohmann::json j) {
    return input_error([&] {
      tool::ConfigNode cfg(j, "config.json");
      parse_order_relaxation_settings(cfg);
      cfg.finish();
    });
  };
  auto e = fails({{"method", "fit"}});
  EXPECT_NE(std::string(e.what()).find("method"), std::string::npos) << e.what();
  e = fails({{"method", "regression"}, {"noise_from", 3.0}});
  EXPECT_NE(std::string(e.what()).find("noise_from"), std::string::npos);
  EXPECT_NE(std::string(e.what()).find("no effect"), std::string::npos) << e.what();
  e = fails({{"method", "regression"}, {"noise_factor", 2.0}});
  EXPECT_NE(std::string(e.what()).find("noise_factor"), std::string::npos) << e.what();
  e = fails({{"method", "decay"}, {"lags_per_decade", 5}});
  EXPECT_NE(std::string(e.what()).find("lags_per_decade"), std::string::npos) << e.what();
  e = fails({{"method", "decay"}, {"max_origins", 5}});
  EXPECT_NE(std::string(e.what()).find("max_origins"), std::string::npos) << e.what();
  e = fails({{"method", "decay"}, {"fit_band", {0.1, 0.02}}});
  EXPECT_NE(std::string(e.what()).find("fit_band"), std::string::npos) << e.what();
  e = fails({{"method", "regression"}, {"fit_band", {0.05, 1.5}}});
  EXPECT_NE(std::string(e.what()).find("fit_band"), std::string::npos) << e.what();
  e = fails(nlohmann::json::object());
  EXPECT_NE(std::string(e.what()).find("method"), std::string::npos) << e.what();
  const auto regression = settings("regression");
  EXPECT_DOUBLE_EQ(regression.band_low, 0.05);
  EXPECT_DOUBLE_EQ(regression.band_high, 0.5);
}

TEST_F(OrderRelaxationTest, MissingObservableNamesTheFileAndPath) {
  SyntheticTrajectory t = carrier({});
  t.observables.clear();
  const std::string path = file("bare.h5");
  t.write(path);
  const auto e = input_error([&] { analyse(settings("decay"), {path}); });
  EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("/observables/order_tensor_rod"), std::string::npos) << e.what();
}

TEST(OrderRelaxationKernels, FullContractionCountsOffDiagonalsTwice) {
  const double a[6] = {1, 2, 3, 4, 5, 6}, b[6] = {0.5, -1, 2, 0.25, -0.5, 1};
  Mat3 A, B;
  A << 1, 4, 5, 4, 2, 6, 5, 6, 3;
  B << 0.5, 0.25, -0.5, 0.25, -1, 1, -0.5, 1, 2;
  EXPECT_NEAR(full_contraction(a, b), (A.array() * B.array()).sum(), 1e-14);
}

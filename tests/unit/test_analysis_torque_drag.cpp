// Method II (spec 20 §6.2) on synthetic tagged axes: rods turning about a tilted torque axis ê at
// ω = D_r βT_ex with angular noise √(2D_r dt) per row and a small out-of-plane wobble, written as
// anisodyn-bd writes them (the observable tagged_axes and the run's external_torque parameters).
// The stage must return D_r(φ) = D_r within 4 standard errors, over rods and replicas and, for a single
// rod in a single run, over time blocks.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "anisodyn/analysis/torque_drag.hpp"
#include "scratch_dir.hpp"
#include "synthetic_trajectory.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;
using anisodyn::testing_support::SyntheticTrajectory;

namespace {

constexpr double kDr = 0.5, kBetaTorque = 10.0, kRowSpacing = 0.01;
const Vec3 kAxis = Vec3(1, 2, 2) / 3.0;

/// `rods` tagged rods (ids 0 …) turning about kAxis for `rows` rows.
SyntheticTrajectory turning_rods(std::size_t rods, std::size_t rows, unsigned seed) {
  SyntheticTrajectory t = anisodyn::testing_support::gaussian_walks(rods + 2, {0.0, rows * kRowSpacing}, Vec3::Zero(), seed);
  t.table = {Species{"rod", Shape::spherocylinder(5.0, 0.1), 1.0, Vec3(1, 1, 2), Vec3(kDr, kDr, 0)}};
  std::vector<std::int64_t> ids;
  for (std::size_t k = 0; k < rods; ++k) ids.push_back(static_cast<std::int64_t>(k));
  t.parameters = {{"external_torque", {{"particles", ids}, {"torque_kT", kBetaTorque}, {"axis", {1, 2, 2}}, {"confinement_kT", 100}}}};
  // a right-handed in-plane basis of the test's own: ê₁ ∝ ê × ẑ, ê₂ = ê × ê₁
  const Vec3 e1 = kAxis.cross(Vec3::UnitZ()).normalized(), e2 = kAxis.cross(e1);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> theta(rods);
  for (auto& th : theta) th = 6.0 * std::generate_canonical<double, 53>(rng);
  std::vector<std::pair<double, std::vector<double>>> table;
  for (std::size_t r = 1; r <= rows; ++r) {
    std::vector<double> row;
    for (std::size_t k = 0; k < rods; ++k) {
      theta[k] += kDr * kBetaTorque * kRowSpacing + std::sqrt(2 * kDr * kRowSpacing) * g(rng);
      const double tilt = 0.1 * g(rng);  // the confinement's wobble out of the plane
      const Vec3 u = std::cos(tilt) * (std::cos(theta[k]) * e1 + std::sin(theta[k]) * e2) + std::sin(tilt) * kAxis;
      row.insert(row.end(), {u.x(), u.y(), u.z()});
    }
    table.emplace_back(r * kRowSpacing, row);
  }
  t.observables.push_back({kTaggedAxes, table});
  return t;
}

class TorqueDragTest : public anisodyn::testing_support::ScratchDirTest {
 protected:
  TorqueDragTest() : ScratchDirTest("torque_drag") {}

  TorqueDragResult run(std::size_t rods, unsigned replicas, unsigned seed) {
    std::vector<std::string> paths;
    for (unsigned r = 0; r < replicas; ++r) {
      paths.push_back(file("drag" + std::to_string(rods) + "_" + std::to_string(r) + ".h5"));
      turning_rods(rods, 2000, seed + r).write(paths.back());
    }
    TorqueDragAnalysis a(paths.size());
    TrajectoryNeeds needs;
    needs.observables = {kTaggedAxes};
    for_each_replica(paths, needs, [&](const Trajectory& t, std::size_t k) { a.accumulate(t, k); }, kIndependentTimes);
    return a.compute();
  }
};

TEST_F(TorqueDragTest, RodsAndReplicasGiveTheKnownRate) {
  const TorqueDragResult r = run(3, 4, 20);
  std::printf("3 rods x 4 replicas: <omega> = %.4f ± %.4f (expected %.4f), D_r(phi) = %.4f ± %.4f (expected %.4f)\n", r.omega.value,
              r.omega.error, kDr * kBetaTorque, r.dr.value, r.dr.error, kDr);
  EXPECT_EQ(r.samples, 12u);
  EXPECT_FALSE(r.time_blocks);
  EXPECT_NEAR(r.dr.value, kDr, 4 * r.dr.error);
  EXPECT_LT(r.dr.error, 0.05 * kDr);
  EXPECT_EQ(r.rods.size(), 12u);
  for (const auto& rod : r.rods) {
    EXPECT_EQ(rod.large_turns, 0u);
    EXPECT_NEAR(rod.mean_axial_square, std::pow(std::sin(0.1), 2), 0.005);
  }
}

TEST_F(TorqueDragTest, OneRodInOneRunUsesCalibratedTimeBlocks) {
  // Eight single-rod runs: their values scatter about D_r (checked against the scatter itself), and
  // the block error of one run agrees with that scatter (mean block SE / sd of the values in 0.5 … 2).
  std::vector<double> values, errors;
  for (unsigned seed = 50; seed < 58; ++seed) {
    const TorqueDragResult r = run(1, 1, seed);
    EXPECT_TRUE(r.time_blocks);
    EXPECT_EQ(r.samples, 10u);
    values.push_back(r.dr.value);
    errors.push_back(r.dr.error);
  }
  const Estimate spread = mean_and_error(values), block_error = mean_and_error(errors);
  const double sd = spread.error * std::sqrt(static_cast<double>(values.size()));
  std::printf("1 rod, 10 blocks, 8 runs: mean D_r(phi) = %.4f ± %.4f (expected %.4f); sd of the runs %.4f, mean block SE %.4f\n",
              spread.value, spread.error, kDr, sd, block_error.value);
  EXPECT_NEAR(spread.value, kDr, 4 * spread.error);
  EXPECT_GT(block_error.value, 0.5 * sd);
  EXPECT_LT(block_error.value, 2.0 * sd);
}

}  // namespace

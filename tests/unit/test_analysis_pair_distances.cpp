// Effective diameter from P_d(x) (spec 20 §5, spec 50 I5): histograms with known moments (a
// uniform band of bins, whose bin-centre variance is (n² − 1)Δ²/12, and counts proportional to the
// bin centres, P ∝ x), replicas' mean and standard error by hand, the study-B box edge, and bad input.
#include <gtest/gtest.h>

#include <cmath>

#include "anisodyn/analysis/pair_distances.hpp"
#include "input_error.hpp"
#include "scratch_dir.hpp"
#include "synthetic_trajectory.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;
using anisodyn::testing_support::input_error;
using anisodyn::testing_support::SyntheticTrajectory;

namespace {

/// `per_bin` pairs in each of the bins [first, last) of 100.
std::vector<double> band(std::size_t first, std::size_t last, double per_bin) {
  std::vector<double> c(100, 0.0);
  for (std::size_t b = first; b < last; ++b) c[b] = per_bin;
  return c;
}

SyntheticTrajectory run_with(const std::vector<double>& counts) {
  SyntheticTrajectory t;
  t.table = {Species{"rod", Shape::spherocylinder(5.0, 0.1), 1.0, Vec3(1, 1, 2), Vec3(0.5, 0.5, 0.0)}};
  t.time = {0.0, 1.0};
  t.position.assign(2, std::vector<Vec3>{Vec3(1, 1, 1)});
  if (!counts.empty()) t.observables.push_back({kPairDistanceObservable, {{1.0, counts}}});
  return t;
}

}  // namespace

TEST(PairDistanceMoments, UniformBandHasTheDiscreteUniformMoments) {
  // 40 bins from x = 0.305 to 0.695: mean 0.5, variance (40² − 1)(0.01)²/12.
  const HistogramMoments m = histogram_moments(band(30, 70, 7.0));
  EXPECT_DOUBLE_EQ(m.pairs, 280.0);
  EXPECT_NEAR(m.mean_x, 0.5, 1e-15);
  EXPECT_NEAR(m.sigma_x, std::sqrt((1600.0 - 1.0) * 1e-4 / 12.0), 1e-14);
  double integral = 0;
  for (double p : m.density) integral += p * 0.01;
  EXPECT_NEAR(integral, 1.0, 1e-14);
  EXPECT_NEAR(m.density[50], 1.0 / 0.4, 1e-12);  // uniform on a band of width 0.4
}

TEST(PairDistanceMoments, CountsProportionalToXGiveTheBinnedLinearLaw) {
  // c_b ∝ x_b: ⟨x⟩ = Σx_b²/Σx_b with Σx_b = 50 and Σx_b² = (Σb² + Σb + 100/4)/10⁴ = 33.3325 for
  // b = 0 … 99; the continuous law P = 2x has ⟨x⟩ = 2/3 and ⟨x²⟩ = 1/2.
  std::vector<double> c(100);
  for (std::size_t b = 0; b < 100; ++b) c[b] = 3.0 * (static_cast<double>(b) + 0.5);
  const HistogramMoments m = histogram_moments(c);
  double sum3 = 0;  // Σ x_b³
  for (std::size_t b = 0; b < 100; ++b) sum3 += std::pow((static_cast<double>(b) + 0.5) / 100, 3);
  const double mean = 33.3325 / 50.0;
  EXPECT_NEAR(m.mean_x, mean, 1e-14);
  EXPECT_NEAR(m.sigma_x, std::sqrt(sum3 / 50.0 - mean * mean), 1e-12);
  EXPECT_NEAR(m.mean_x, 2.0 / 3.0, 2e-5);                              // binning error O(Δx²)
  EXPECT_NEAR(m.sigma_x, std::sqrt(0.5 - 4.0 / 9.0), 1e-4);
}

TEST(PairDistanceMoments, BoxEdgeOfTheStudy) {
  // Spec 20 §1: with D_eff = D = 14.8 nm and L = 0.88 µm the edge is 2.080 µm.
  EXPECT_NEAR(study_box_edge(0.88, 0.0148), 2.080, 5e-4);
}

class PairDistanceFileTest : public anisodyn::testing_support::ScratchDirTest {
 protected:
  PairDistanceFileTest() : ScratchDirTest("pair-distances") {}
  PairDistanceAnalysis analyse(const std::vector<std::vector<double>>& histograms) {
    std::vector<std::string> paths;
    for (std::size_t r = 0; r < histograms.size(); ++r) {
      paths.push_back(file("rep" + std::to_string(r) + ".h5"));
      run_with(histograms[r]).write(paths.back());
    }
    PairDistanceAnalysis a(0.1, 5.0);
    TrajectoryNeeds needs;
    needs.observables = {kPairDistanceObservable};
    for_each_replica(paths, needs, [&](const Trajectory& t, std::size_t) { a.accumulate(t); });
    return a;
  }
};

TEST_F(PairDistanceFileTest, ReplicasGiveMeanAndStandardErrorByHand) {
  // Bands centred on 0.5, 0.4 and 0.6 (⟨x⟩ per replica) of equal width: ⟨x⟩ = 0.5 ± 0.1/√3, σ_x
  // the same in each (standard error 0).
  const PairDistanceResult r = analyse({band(30, 70, 5.0), band(20, 60, 2.0), band(40, 80, 1.0)}).compute();
  EXPECT_NEAR(r.mean_x.value, 0.5, 1e-14);
  EXPECT_NEAR(r.mean_x.error, 0.1 / std::sqrt(3.0), 1e-14);
  EXPECT_NEAR(r.sigma_x.value, std::sqrt(1599e-4 / 12.0), 1e-14);
  EXPECT_NEAR(r.sigma_x.error, 0.0, 1e-14);
  EXPECT_NEAR(r.effective_diameter.value, 0.05, 1e-15);
  EXPECT_NEAR(r.effective_diameter.error, 0.01 / std::sqrt(3.0), 1e-15);
  EXPECT_EQ(r.replica_pairs, (std::vector<double>{200.0, 80.0, 40.0}));
  EXPECT_DOUBLE_EQ(r.counts[25], 2.0);
  EXPECT_DOUBLE_EQ(r.counts[50], 8.0);
  // P_d of bin 50 (x = 0.505): 2.5 in every band; of bin 25: 2.5 in the second band only.
  EXPECT_NEAR(r.density[50], 2.5, 1e-12);
  EXPECT_NEAR(r.density_error[50], 0.0, 1e-12);
  EXPECT_NEAR(r.density[25], 2.5 / 3.0, 1e-12);
  EXPECT_NEAR(r.density_error[25], 2.5 / 3.0, 1e-12);  // sd of (0, 2.5, 0) / √3 = (2.5/√3)/√3
  // Box edge (250 π L² D⟨x⟩)^(1/3); jackknife over the three leave-one-out means ⟨x⟩ = 0.5, 0.55, 0.45.
  const double edge = study_box_edge(5.0, 0.05);
  std::vector<double> loo{study_box_edge(5.0, 0.1 * 0.5), study_box_edge(5.0, 0.1 * 0.55), study_box_edge(5.0, 0.1 * 0.45)};
  const double m = (loo[0] + loo[1] + loo[2]) / 3;
  double ss = 0;
  for (double v : loo) ss += (v - m) * (v - m);
  EXPECT_NEAR(r.box_edge.value, edge, 1e-12);
  EXPECT_NEAR(r.box_edge.error, std::sqrt(2.0 / 3.0 * ss), 1e-12);
}

TEST_F(PairDistanceFileTest, MissingOrEmptyHistogramNamesTheFileAndPath) {
  auto e = input_error([&] { analyse({{}}); });
  EXPECT_NE(std::string(e.what()).find(file("rep0.h5")), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("/observables/pair_distance_histogram"), std::string::npos) << e.what();
  e = input_error([&] { analyse({std::vector<double>(100, 0.0)}); });
  EXPECT_NE(std::string(e.what()).find("/observables/pair_distance_histogram/value"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("no interacting pair"), std::string::npos) << e.what();
}

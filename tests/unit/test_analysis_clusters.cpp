// Cluster analyses (spec 50 §5) on PLANTED configurations with known answers: dipolar chains of
// known lengths (exact N(l), X_c, <l>_n, <l>_w), a chain across the periodic boundary, side-by-side
// cubes that must not bond, aligned board clusters for the nematic criterion, a transition matrix
// from two frames with known moves, the Wertheim fit (exact and multinomial data), DBSCAN on
// planted blobs, the knee rule and the βu_max calibration of a planted dimer blob.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "anisodyn/analysis/dbscan.hpp"
#include "anisodyn/analysis/dipolar_clusters.hpp"
#include "anisodyn/analysis/nematic_clusters.hpp"
#include "anisodyn/analysis/union_find.hpp"
#include "anisodyn/interactions/dipolar_pair.hpp"
#include "input_error.hpp"
#include "scratch_dir.hpp"
#include "synthetic_trajectory.hpp"
#include "time_window.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;
using anisodyn::testing_support::input_error;

namespace {

constexpr double kGamma = 13.0;  // γ of the DMC cube studies; bond cut-off σ (13/3.2)^{1/3} ≈ 1.60σ
constexpr double kSpacing = 1.05;  // stacked neighbours: βu = −γ/1.05³ ≈ −11.2 < −3.2

/// βu of spec 50 E2 written out here independently of the library.
double reference_energy(double par, double perp) {
  const double r2 = par * par + perp * perp, r = std::sqrt(r2);
  return 0.5 * kGamma / (r * r * r) * (1.0 - 3.0 * par * par / r2);
}

DipolarBondRule cube_rule() {
  DipolarBondRule r;
  r.gamma = kGamma;
  return r;
}

/// A Trajectory built in memory: frames of positions (taken as given, no unwrapping) and axes.
Trajectory make_trajectory(const std::vector<double>& time, const std::vector<std::vector<Vec3>>& pos, const Vec3& box,
                           const std::vector<std::vector<Quat>>& orient = {}) {
  Trajectory t;
  t.path = "planted";
  t.frames = time.size();
  t.particles = pos.front().size();
  t.time = time;
  for (std::size_t f = 0; f < t.frames; ++f) {
    t.step.push_back(static_cast<std::int64_t>(f));
    for (int a = 0; a < 3; ++a) t.box.push_back(box[a]);
    for (std::size_t i = 0; i < t.particles; ++i) {
      for (int a = 0; a < 3; ++a) t.position.push_back(pos[f][i][a]);
      const Quat q = orient.empty() ? Quat::Identity() : orient[f][i];
      t.orientation.insert(t.orientation.end(), {q.w(), q.x(), q.y(), q.z()});
    }
  }
  t.species.assign(t.particles, 0);
  for (std::size_t i = 0; i < t.particles; ++i) t.id.push_back(static_cast<std::int64_t>(i));
  return t;
}

/// Straight chains along z of the given lengths on x–y lattice sites 6σ apart, plus free cubes on
/// their own sites (every site pair is far beyond the bond cut-off).
std::vector<Vec3> planted_chains(const std::vector<int>& lengths, int free_cubes) {
  std::vector<Vec3> r;
  int site = 0;
  auto origin = [&]() { const int s = site++; return Vec3(3.0 + 6.0 * (s % 5), 3.0 + 6.0 * (s / 5), 5.0); };
  for (int l : lengths) {
    const Vec3 o = origin();
    for (int k = 0; k < l; ++k) r.push_back(o + Vec3(0, 0, kSpacing * k));
  }
  for (int k = 0; k < free_cubes; ++k) r.push_back(origin());
  return r;
}

std::vector<std::size_t> sorted_sizes(const Components& c) {
  std::vector<std::size_t> s = c.size;
  std::sort(s.begin(), s.end());
  return s;
}

}  // namespace

// ---- union-find -----------------------------------------------------------------------------------

TEST(UnionFind, ComponentsOfAKnownGraph) {
  // 0–1–2, 3–4, 5 alone, 6–7 joined twice
  const Components c = connected_components(8, {{0, 1}, {2, 1}, {3, 4}, {6, 7}, {7, 6}});
  EXPECT_EQ(c.count(), 4u);
  EXPECT_EQ(c.label[0], c.label[2]);
  EXPECT_NE(c.label[0], c.label[3]);
  EXPECT_EQ(c.size[c.label[0]], 3u);
  EXPECT_EQ(c.size[c.label[5]], 1u);
  EXPECT_EQ(c.size_of_each(), (std::vector<std::size_t>{3, 3, 3, 2, 2, 1, 2, 2}));
}

// ---- E2 / E4 ---------------------------------------------------------------------------------------

TEST(DipolarClusters, PlantedChainsGiveExactSizes) {
  // 3 chains of 2, 2 of 3, 1 of 5 and 4 free cubes
  const auto r = planted_chains({2, 2, 2, 3, 3, 5}, 4);
  const Components c = dipolar_clusters(r, Box(Vec3(30, 30, 30)), cube_rule());
  EXPECT_EQ(sorted_sizes(c), (std::vector<std::size_t>{1, 1, 1, 1, 2, 2, 2, 3, 3, 5}));
}

TEST(DipolarClusters, ChainAcrossThePeriodicBoundaryIsOneCluster) {
  // a 5-chain along z through z = L (positions as stored, wrapped into the box) and one along x
  const double L = 20;
  std::vector<Vec3> r;
  for (double z : {17.9, 17.9 + kSpacing, 17.9 + 2 * kSpacing - L, 17.9 + 3 * kSpacing - L, 17.9 + 4 * kSpacing - L}) r.emplace_back(5, 5, z);
  DipolarBondRule rule = cube_rule();
  rule.field = Vec3::UnitX();
  for (double x : {19.5, 0.55, 1.6}) r.emplace_back(x, 12, 12);
  const Components c = dipolar_clusters(r, Box(Vec3(L, L, L)), rule);
  // along x the field is x: the x-chain bonds across x = L; the z-chain is side-by-side for Ê = x
  EXPECT_EQ(c.size[c.label[5]], 3u);
  EXPECT_EQ(c.size[c.label[0]], 1u);
  rule.field = Vec3::UnitZ();
  const Components cz = dipolar_clusters(r, Box(Vec3(L, L, L)), rule);
  EXPECT_EQ(cz.size[cz.label[0]], 5u);
  EXPECT_EQ(cz.size[cz.label[5]], 1u);
}

TEST(DipolarClusters, SideBySideCubesAreNotBonded) {
  const DipolarBondRule rule = cube_rule();
  // θ = 90°: βu = +γ/(2 r³) > 0
  EXPECT_DOUBLE_EQ(dipolar_pair_energy(Vec3(kSpacing, 0, 0), rule.field, rule.gamma), 0.5 * kGamma / std::pow(kSpacing, 3));
  EXPECT_DOUBLE_EQ(dipolar_pair_energy(Vec3(0, 0, kSpacing), rule.field, rule.gamma), -kGamma / std::pow(kSpacing, 3));
  const std::vector<Vec3> r{{5, 5, 5}, {5 + kSpacing, 5, 5}, {5, 5 + 1.0, 5}};
  EXPECT_TRUE(dipolar_bonds(r, Box(Vec3(20, 20, 20)), rule).empty());
  // the same cubes stacked along the field are bonded
  const std::vector<Vec3> s{{5, 5, 5}, {5, 5, 5 + kSpacing}};
  EXPECT_EQ(dipolar_bonds(s, Box(Vec3(20, 20, 20)), rule).size(), 1u);
  // threshold: a pair at θ = 0 with βu just above −3.2 is not bonded, just below is
  const double r_edge = std::cbrt(kGamma / 3.2);
  EXPECT_TRUE(dipolar_bonds({{5, 5, 5}, {5, 5, 5 + r_edge * 1.001}}, Box(Vec3(20, 20, 20)), rule).empty());
  EXPECT_EQ(dipolar_bonds({{5, 5, 5}, {5, 5, 5 + r_edge * 0.999}}, Box(Vec3(20, 20, 20)), rule).size(), 1u);
}

class DipolarChainTest : public anisodyn::testing_support::ScratchDirTest {
 protected:
  DipolarChainTest() : ScratchDirTest("clusters") {}
};

TEST_F(DipolarChainTest, PlantedChainsGiveExactChainStatisticsThroughTheFileReader) {
  const auto r = planted_chains({2, 2, 2, 3, 3, 5}, 4);
  testing_support::SyntheticTrajectory syn;
  syn.box = Vec3(30, 30, 30);
  syn.time = {0.0, 1.0, 2.0};
  syn.position.assign(3, r);
  std::vector<std::string> paths{file("a.h5"), file("b.h5")};
  for (const auto& p : paths) syn.write(p);
  DipolarClusterSettings s;
  s.rule = cube_rule();
  DipolarChainAnalysis a(s);
  TrajectoryNeeds needs;
  needs.positions = true;
  for_each_replica(paths, needs, [&](const Trajectory& t, std::size_t) { a.accumulate(t, -1); });
  const DipolarChainResult res = a.compute();
  const double n = 21;  // cubes
  ASSERT_EQ(res.sizes, 5u);
  ASSERT_EQ(res.time.size(), 3u);
  const std::vector<double> expected_x{4 / n, 3 / n, 2 / n, 0.0, 1 / n};
  for (std::size_t f = 0; f < 3; ++f) {
    for (std::size_t l = 0; l < 5; ++l) EXPECT_NEAR(res.x[f * 5 + l], expected_x[l], 1e-15) << "l=" << l + 1;
    EXPECT_NEAR(res.chain_fraction[f], 17 / n, 1e-15);
    EXPECT_NEAR(res.mean_length[f], 17.0 / 6.0, 1e-15);                // (2·3 + 3·2 + 5)/(3 + 2 + 1)
    EXPECT_NEAR(res.weight_mean_length[f], 55.0 / 17.0, 1e-15);       // (4·3 + 9·2 + 25)/17
  }
  EXPECT_NEAR(res.plateau.value, 17 / n, 1e-15);
  EXPECT_DOUBLE_EQ(res.response_time.value, 0.0);  // already on the plateau at the switch
}

TEST(DipolarChainAnalysis, ResponseTimeOfAPlantedGrowthCurve) {
  // 10 sites, 20 cubes; at frame f the first min(2f, 10) sites hold a bonded dimer, the others a
  // pair 3σ apart along z. X_c = 0, .2, .4, .6, .8, 1, 1, 1, 1, 1 at t = 0 … 9; plateau (t ≥ 6.75)
  // = 1, so 0.95 is crossed between t = 4 (0.8) and 5 (1.0): t_r = 4.75.
  std::vector<double> time;
  std::vector<std::vector<Vec3>> pos;
  for (int f = 0; f < 10; ++f) {
    time.push_back(f);
    std::vector<Vec3> r;
    for (int s = 0; s < 10; ++s) {
      const Vec3 o(4.0 + 8.0 * s, 5, 3);
      r.push_back(o);
      r.push_back(o + Vec3(0, 0, s < std::min(2 * f, 10) ? kSpacing : 3.0));
    }
    pos.push_back(r);
  }
  DipolarClusterSettings s;
  s.rule = cube_rule();
  DipolarChainAnalysis a(s);
  const Trajectory t = make_trajectory(time, pos, Vec3(80, 10, 10));
  a.accumulate(t, -1);
  a.accumulate(t, -1);
  const DipolarChainResult r = a.compute();
  EXPECT_NEAR(r.chain_fraction[4], 0.8, 1e-15);
  EXPECT_NEAR(r.plateau.value, 1.0, 1e-15);
  EXPECT_NEAR(r.response_time.value, 4.75, 1e-12);
  EXPECT_NEAR(r.response_time.error, 0.0, 1e-12);  // identical replicas
  EXPECT_NEAR(r.plateau_t_min, 6.75, 1e-12);
}

// ---- E5 --------------------------------------------------------------------------------------------

TEST(DipolarChainAnalysis, TransitionMatrixOfTwoPlantedFrames) {
  // t = 0: chain {0,1,2}, chain {3,4}, free 5, 6.  t = 0.3: {0,1} stays, 2 leaves; {3,4} takes 5; 6 free.
  auto site = [](int s) { return Vec3(4.0 + 8.0 * s, 5, 5); };
  const Vec3 up(0, 0, kSpacing);
  std::vector<Vec3> a{site(0), site(0) + up, site(0) + 2 * up, site(1), site(1) + up, site(2), site(3)};
  std::vector<Vec3> b = a;
  b[2] = site(0) + Vec3(0, 0, 5.0);   // 3 → 2 + 1
  b[5] = site(1) + 2 * up;            // 2 + 1 → 3
  DipolarClusterSettings s;
  s.rule = cube_rule();
  s.transition_times = {0.0};
  DipolarChainAnalysis an(s);
  an.accumulate(make_trajectory({0.0, 0.3}, {a, b}, Vec3(40, 10, 10)), -1);
  const DipolarChainResult r = an.compute();
  ASSERT_EQ(r.transitions.size(), 1u);
  const TransitionMatrix& m = r.transitions[0];
  ASSERT_EQ(m.sizes, 3u);
  EXPECT_EQ(m.frame_pairs, 1u);
  auto p = [&](int l, int lp) { return m.probability[static_cast<std::size_t>((l - 1) * 3 + (lp - 1))]; };
  EXPECT_DOUBLE_EQ(p(1, 1), 0.5);   // cube 6
  EXPECT_DOUBLE_EQ(p(1, 3), 0.5);   // cube 5
  EXPECT_TRUE(std::isnan(p(1, 2))); // zero probability: blank
  EXPECT_DOUBLE_EQ(p(2, 3), 1.0);   // cubes 3, 4
  EXPECT_TRUE(std::isnan(p(2, 1)));
  EXPECT_DOUBLE_EQ(p(3, 2), 2.0 / 3.0);  // cubes 0, 1
  EXPECT_DOUBLE_EQ(p(3, 1), 1.0 / 3.0);  // cube 2
  EXPECT_EQ(m.row_count, (std::vector<double>{2, 2, 3}));
}

TEST(DipolarChainAnalysis, TransitionTimeWithoutAFramePairIsAnInputError) {
  DipolarClusterSettings s;
  s.rule = cube_rule();
  s.transition_times = {0.0};
  s.transition_lag = 0.3;
  DipolarChainAnalysis an(s);
  const std::vector<Vec3> r{{1, 1, 1}, {5, 5, 5}};
  const auto e = input_error([&] { an.accumulate(make_trajectory({0.0, 1.0}, {r, r}, Vec3(10, 10, 10)), -1); });
  EXPECT_EQ(e.json_path(), "transition_times");
}

// ---- E6 --------------------------------------------------------------------------------------------

TEST(Wertheim, RecoversPbFromExactFractions) {
  for (double p : {0.2, 0.55, 0.9}) {
    std::vector<double> x, var_uniform, var_relative;
    for (int l = 1; l <= 200; ++l) {
      const double v = (1 - p) * (1 - p) * std::pow(p, l - 1);  // X_eq written out independently
      x.push_back(v);
      var_uniform.push_back(1.0);
      var_relative.push_back(std::pow(0.01 * v, 2));
    }
    const WertheimFit a = fit_wertheim(x, var_uniform), b = fit_wertheim(x, var_relative);
    EXPECT_NEAR(a.p_b, p, 1e-7) << p;
    EXPECT_NEAR(b.p_b, p, 1e-9) << p;
    for (double res : b.residual) EXPECT_NEAR(res, 0.0, 1e-9);
  }
}

TEST(Wertheim, RecoversPbFromMultinomialSamplesWithinFourStandardErrors) {
  // per replica M clusters with sizes drawn from P(l) = (1 − p) p^{l−1}: E N(l)/E N_cube = X_eq(l)
  const double p = 0.5;
  const int replicas = 20, clusters = 2000, lmax = 40;
  std::mt19937_64 rng(20240611);
  std::geometric_distribution<int> geo(1 - p);
  CurveSamples samples;
  for (int r = 0; r < replicas; ++r) {
    std::vector<double> n(lmax, 0.0);
    double cubes = 0;
    for (int c = 0; c < clusters; ++c) {
      const int l = 1 + geo(rng);
      cubes += l;
      if (l <= lmax) n[static_cast<std::size_t>(l - 1)] += 1;
    }
    for (auto& v : n) v /= cubes;
    samples.add(n);
  }
  const WertheimFit f = fit_wertheim(samples);
  ASSERT_GT(f.error, 0.0);
  EXPECT_LT(f.error, 0.01);
  EXPECT_NEAR(f.p_b, p, 4 * f.error);
  EXPECT_EQ(f.residual.size(), f.length.size());
}

// ---- E1 --------------------------------------------------------------------------------------------

namespace {

Quat pointing(const Vec3& u) { return Quat::FromTwoVectors(Vec3::UnitZ(), u.normalized()); }

NematicClusterSettings prolate_settings() {
  NematicClusterSettings s;  // thesis Table 4.7, W* = 1 (ê_L)
  s.axis = 2;
  s.k1 = 0.85;
  s.k2 = 0.90;
  s.k_par = 12.25;
  s.k_perp = 1.55;
  return s;
}

/// Cluster A: 5 boards with ê_L ≈ z side by side along x (1.2 apart); cluster B: 4 boards with
/// ê_L ≈ x side by side along y; 6 randomly oriented boards 30 apart from everything. Tilts ≤ 2°.
void planted_boards(std::vector<Vec3>& r, std::vector<Quat>& q, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  auto tilt = [&](const Vec3& a) {
    Vec3 t(u(rng), u(rng), u(rng));
    t -= t.dot(a) * a;
    return (a + std::tan(2.0 * M_PI / 180) * 0.99 * t.normalized()).normalized();
  };
  for (int k = 0; k < 5; ++k) {
    r.emplace_back(10 + 1.2 * k, 10, 10 + 0.5 * u(rng));
    q.push_back(pointing(tilt(Vec3::UnitZ())));
  }
  for (int k = 0; k < 4; ++k) {
    r.emplace_back(60 + 0.5 * u(rng), 60 + 1.2 * k, 10);
    q.push_back(pointing(tilt(Vec3::UnitX())));
  }
  for (int k = 0; k < 6; ++k) {
    r.emplace_back(10 + 30 * (k % 3), 40 + 30 * (k / 3 % 2), 60);
    q.push_back(pointing(Vec3(u(rng), u(rng), u(rng))));
  }
}

}  // namespace

TEST(NematicClusters, PlantedAlignedClustersAndIsolatedBoards) {
  std::mt19937_64 rng(7);
  std::vector<Vec3> r;
  std::vector<Quat> q;
  planted_boards(r, q, rng);
  std::vector<Vec3> e;
  for (const auto& x : q) e.push_back(x.toRotationMatrix().col(2));
  const NematicClustering c = nematic_clusters(r, e, Box(Vec3(100, 100, 100)), prolate_settings());
  EXPECT_TRUE(c.converged);
  EXPECT_EQ(c.size.size(), 8u);
  for (int k = 1; k < 5; ++k) EXPECT_EQ(c.label[k], c.label[0]);
  for (int k = 6; k < 9; ++k) EXPECT_EQ(c.label[k], c.label[5]);
  EXPECT_EQ(c.size[c.label[0]], 5u);
  EXPECT_EQ(c.size[c.label[5]], 4u);
  for (int k = 9; k < 15; ++k) EXPECT_EQ(c.size[c.label[k]], 1u);
  EXPECT_GT(std::abs(c.director[c.label[0]].z()), std::cos(2.0 * M_PI / 180));
  EXPECT_GT(std::abs(c.director[c.label[5]].x()), std::cos(2.0 * M_PI / 180));
}

TEST(NematicClusters, PairBelowTheOrderThresholdIsSplit) {
  // Two boards side by side: U_local of a pair is (1 + 3|cos θ|)/4, so |cos θ| = 0.86 (> K1) gives
  // U = 0.895 ≤ K2 = 0.9 (peeled into singletons) and |cos θ| = 0.9 gives U = 0.925 (kept).
  for (const auto& [c, expected] : {std::pair{0.86, 1u}, std::pair{0.90, 2u}}) {
    const std::vector<Vec3> r{{10, 10, 10}, {11, 10, 10}};
    const std::vector<Vec3> e{Vec3::UnitZ(), Vec3(0, std::sqrt(1 - c * c), c)};
    const NematicClustering out = nematic_clusters(r, e, Box(Vec3(40, 40, 40)), prolate_settings());
    EXPECT_EQ(out.size[out.label[0]], expected) << "cos = " << c;
  }
  // end to end along the axis (|r_par| = 13 > K_par): not a cluster even when parallel
  const NematicClustering far = nematic_clusters({{10, 10, 10}, {10, 10, 23}}, {Vec3::UnitZ(), Vec3::UnitZ()},
                                                 Box(Vec3(40, 40, 40)), prolate_settings());
  EXPECT_EQ(far.size.size(), 2u);
}

TEST(NematicClusterAnalysis, AggregatesHistogramTotalsAndDirectorAngles) {
  std::mt19937_64 rng(11);
  std::vector<Vec3> r;
  std::vector<Quat> q;
  planted_boards(r, q, rng);
  NematicClusterAnalysis a(prolate_settings(), 2);
  const Trajectory t = make_trajectory({0.0, 1.0}, {r, r}, Vec3(100, 100, 100), {q, q});
  a.accumulate(t, -1);
  a.accumulate(t, -1);
  const NematicClusterResult res = a.compute();
  EXPECT_EQ(res.configurations, 4u);
  ASSERT_EQ(res.mean_count.size(), 5u);
  EXPECT_DOUBLE_EQ(res.mean_count[0], 6.0);
  EXPECT_DOUBLE_EQ(res.mean_count[1], 0.0);
  EXPECT_DOUBLE_EQ(res.mean_count[3], 1.0);
  EXPECT_DOUBLE_EQ(res.mean_count[4], 1.0);
  EXPECT_DOUBLE_EQ(res.total.value, 8.0);
  EXPECT_DOUBLE_EQ(res.largest_fraction.value, 5.0 / 15.0);
  // directors: one ≈ z, one ≈ x (tilts ≤ 2° keep |cos| in the first and last of 20 bins)
  const double w = 1.0 / 20;
  EXPECT_DOUBLE_EQ(res.cos_density[2].back(), 0.5 / w);
  EXPECT_DOUBLE_EQ(res.cos_density[2].front(), 0.5 / w);
  EXPECT_DOUBLE_EQ(res.cos_density[0].back(), 0.5 / w);
  EXPECT_DOUBLE_EQ(res.cos_density[1].front(), 1.0 / w);
}

TEST_F(DipolarChainTest, AWindowKeepsTrajectoryTimeAndFileFrameIndices) {
  // dipolar chains: the time series and t_r stay in trajectory time (not time since the window start)
  testing_support::SyntheticTrajectory syn;
  syn.box = Vec3(30, 30, 30);
  syn.time = {0.0, 1.0, 2.0, 3.0};
  syn.position.assign(4, planted_chains({2, 3}, 4));
  const std::string chains = file("chains.h5");
  syn.write(chains);
  TrajectoryNeeds needs;
  needs.positions = true;
  needs.window = testing_support::time_window(1.0, std::nullopt);
  DipolarClusterSettings ds;
  ds.rule = cube_rule();
  DipolarChainAnalysis d(ds);
  for_each_replica({chains}, needs, [&](const Trajectory& t, std::size_t) { d.accumulate(t, -1); });
  const DipolarChainResult dr = d.compute();
  EXPECT_EQ(dr.time, (std::vector<double>{1.0, 2.0, 3.0}));
  EXPECT_DOUBLE_EQ(dr.response_time.value, 1.0);  // on the plateau at the window's first frame, t = 1
  // nematic clusters: a configuration's frame is its index in the file
  std::mt19937_64 rng(13);
  std::vector<Vec3> r;
  std::vector<Quat> q;
  planted_boards(r, q, rng);
  testing_support::SyntheticTrajectory boards;
  boards.box = Vec3(100, 100, 100);
  boards.time = {0.0, 1.0, 2.0, 3.0};
  boards.position.assign(4, r);
  boards.orientation.assign(4, q);
  boards.table = {Species{"board", Shape::cuboid(1, 1, 12), 1.0, Vec3::Ones(), Vec3::Ones()}};
  const std::string nematic = file("boards.h5");
  boards.write(nematic);
  needs.orientations = true;
  needs.window = testing_support::time_window(2.0, std::nullopt);
  NematicClusterAnalysis n(prolate_settings(), 1);
  for_each_replica({nematic}, needs, [&](const Trajectory& t, std::size_t) { n.accumulate(t, -1); });
  const NematicClusterResult nr = n.compute();
  ASSERT_EQ(nr.per_configuration.size(), 2u);
  EXPECT_EQ(nr.per_configuration[0].frame, 2u);
  EXPECT_EQ(nr.per_configuration[1].frame, 3u);
  EXPECT_EQ(nr.per_configuration[1].time, 3.0);
}

TEST(NematicClusters, ThresholdOutsideItsRangeIsAnInputError) {
  NematicClusterSettings s = prolate_settings();
  s.k1 = 1.5;
  const auto e = input_error([&] { nematic_clusters({{0, 0, 0}}, {Vec3::UnitZ()}, Box(Vec3(10, 10, 10)), s); });
  EXPECT_EQ(e.json_path(), "K1");
  s.k1 = 0.0;
  EXPECT_EQ(input_error([&] { NematicClusterAnalysis(s, 1, "cfg.json"); }).file(), "cfg.json");
  s.k1 = 0.85;
  s.k_perp = -1;
  EXPECT_EQ(input_error([&] { nematic_clusters({{0, 0, 0}}, {Vec3::UnitZ()}, Box(Vec3(10, 10, 10)), s); }).json_path(), "K_perp");
}

// ---- E3 --------------------------------------------------------------------------------------------

TEST(Dbscan, FindsPlantedBlobsAndLabelsSparsePointsAsNoise) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  auto disc = [&](double cx, double cy, int n, std::vector<Point2>& out) {
    for (int k = 0; k < n; ++k) {
      const double rr = 0.05 * std::sqrt(u(rng)), phi = 2 * M_PI * u(rng);
      out.push_back({cx + rr * std::cos(phi), cy + rr * std::sin(phi)});
    }
  };
  std::vector<Point2> p;
  disc(1.0, 0.1, 50, p);
  disc(0.3, 1.5, 40, p);
  // sparse uniform points kept 0.3 away from the blob centres: each has < 10 neighbours in 0.1 and no core neighbour
  int sparse = 0;
  while (sparse < 30) {
    const Point2 q{2 * u(rng), 2 * u(rng)};
    if (std::hypot(q.x - 1.0, q.y - 0.1) < 0.3 || std::hypot(q.x - 0.3, q.y - 1.5) < 0.3) continue;
    p.push_back(q);
    ++sparse;
  }
  const DbscanLabels l = dbscan(p, 0.1, 10);
  EXPECT_EQ(l.clusters, 2);
  for (int k = 1; k < 50; ++k) EXPECT_EQ(l.label[k], l.label[0]);
  for (int k = 51; k < 90; ++k) EXPECT_EQ(l.label[k], l.label[50]);
  EXPECT_NE(l.label[0], l.label[50]);
  EXPECT_GE(l.label[0], 0);
  for (std::size_t k = 90; k < p.size(); ++k) EXPECT_EQ(l.label[k], kDbscanNoise);
  EXPECT_EQ(l.noise, 30u);
}

TEST(Dbscan, KneeIsTheCornerOfAHockeyStickCurve) {
  std::vector<double> d;
  for (int k = 0; k < 90; ++k) d.push_back(0.01 * k / 89.0);
  for (int k = 0; k < 10; ++k) d.push_back(0.5 + 0.5 * k / 9.0);
  EXPECT_EQ(knee_index(d), 89u);
  // the k-NN distances of 4 collinear points 1 apart, k = 1: all 1
  const std::vector<Point2> line{{0, 0}, {1, 0}, {2, 0}, {3, 0}};
  EXPECT_EQ(sorted_knn_distances(line, 1), (std::vector<double>{1, 1, 1, 1}));
  EXPECT_EQ(sorted_knn_distances(line, 2), (std::vector<double>{1, 1, 2, 2}));
}

TEST(DbscanCalibration, BondThresholdOfAPlantedDimerBlobIsTheMaximumEnergyOverIt) {
  // 30 dimers on sites 6σ apart (one across the periodic boundary in z), separations r_∥ ∈ 1 ± 0.05,
  // r_⊥ ∈ [0, 0.08) at random azimuth: one point per dimer, all within Eps = 0.2 of each other.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  const Vec3 box(36, 36, 36);
  std::vector<Vec3> r;
  double expected = -1e300;
  for (int s = 0; s < 30; ++s) {
    const Vec3 o(3.0 + 6.0 * (s % 6), 3.0 + 6.0 * (s / 6), s == 0 ? 35.5 : 3.0);
    const double par = 1.0 + 0.1 * (u(rng) - 0.5), perp = 0.08 * u(rng), phi = 2 * M_PI * u(rng);
    Vec3 partner = o + Vec3(perp * std::cos(phi), perp * std::sin(phi), par);
    if (partner.z() >= box.z()) partner.z() -= box.z();
    r.push_back(o);
    r.push_back(partner);
    expected = std::max(expected, reference_energy(par, perp));
  }
  DbscanCalibrationSettings s;
  s.rule = cube_rule();
  s.eps = 0.2;
  const auto points = neighbour_separation_points(r, Box(box), s);
  EXPECT_EQ(points.size(), 30u);
  DbscanCalibration cal(s);
  cal.accumulate(make_trajectory({0.0}, {r}, box), -1);
  const DbscanCalibrationResult res = cal.compute();
  ASSERT_EQ(res.bu_max.size(), 3u);
  const BondCalibration& b = res.configurations[0].per_factor[1];  // Eps × 1
  EXPECT_EQ(b.clusters, 1);
  EXPECT_EQ(b.cluster_points, 30u);
  EXPECT_NEAR(b.bu_max, expected, 1e-12 * std::abs(expected));
  EXPECT_NEAR(res.bu_max[1].value, expected, 1e-12 * std::abs(expected));
  EXPECT_EQ(res.used[1], 1u);
}

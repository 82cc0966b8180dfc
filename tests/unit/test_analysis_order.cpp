// Order parameters (spec 50 §3) on synthetic orientations with known answers: uniformly random
// orientations (U at the finite-N baseline from an independent Monte Carlo, ⟨S_i⟩ = 0,
// ⟨max_k (n·e_k)²⟩ = (π + 2√3)/(3π)), perfect alignment (U = B_2 = S_rod = S_cube = 1), exact
// biaxial mixtures (B_2 = |2p − 1|), the dipolar chain rule on hand-built configurations, and the
// order stage over replicas (common time grid, run averages, phase verdict, bad input).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "anisodyn/analysis/order_parameters.hpp"
#include "anisodyn/analysis/species_selection.hpp"
#include "anisodyn/core/error.hpp"
#include "anisodyn/system/order.hpp"
#include "input_error.hpp"
#include "scratch_dir.hpp"
#include "synthetic_trajectory.hpp"
#include "time_window.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;
using anisodyn::testing_support::input_error;

namespace {

/// Uniform random rotation from a normalised 4-D Gaussian (independent of the engine's Shoemake map).
Quat random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  Quat q(g(rng), g(rng), g(rng), g(rng));
  return q.normalized();
}

/// Largest eigenvalue of a symmetric 3×3 matrix by the trigonometric closed form (Smith 1961),
/// independent of the Eigen solver used by the code under test.
double largest_eigenvalue_closed_form(const Mat3& a) {
  const double p1 = a(0, 1) * a(0, 1) + a(0, 2) * a(0, 2) + a(1, 2) * a(1, 2);
  const double q = a.trace() / 3.0;
  const double p2 = (a(0, 0) - q) * (a(0, 0) - q) + (a(1, 1) - q) * (a(1, 1) - q) + (a(2, 2) - q) * (a(2, 2) - q) + 2 * p1;
  const double p = std::sqrt(p2 / 6.0);
  if (p == 0) return q;
  const Mat3 b = (a - q * Mat3::Identity()) / p;
  const double r = std::clamp(b.determinant() / 2.0, -1.0, 1.0);
  return q + 2 * p * std::cos(std::acos(r) / 3.0);
}

struct MeanSe {
  double mean = 0, se = 0;
};
MeanSe mean_se(const std::vector<double>& x) {
  MeanSe m;
  for (double v : x) m.mean += v;
  m.mean /= static_cast<double>(x.size());
  double var = 0;
  for (double v : x) var += (v - m.mean) * (v - m.mean);
  m.se = std::sqrt(var / static_cast<double>(x.size() - 1) / static_cast<double>(x.size()));
  return m;
}

std::vector<Mat3> to_matrices(const std::vector<Quat>& q) {
  std::vector<Mat3> r;
  for (const auto& x : q) r.push_back(x.toRotationMatrix());
  return r;
}

/// An in-memory trajectory (no file): orientations [frame][particle], positions optional.
Trajectory make_trajectory(const std::vector<std::vector<Quat>>& q, const std::vector<double>& time,
                           const std::vector<std::vector<Vec3>>& pos = {}, const Vec3& box = Vec3(10, 10, 10)) {
  Trajectory t;
  t.path = "memory";
  t.frames = q.size();
  t.particles = q.front().size();
  t.time = time;
  t.step.resize(t.frames);
  for (std::size_t f = 0; f < t.frames; ++f) {
    t.step[f] = static_cast<std::int64_t>(f);
    for (int a = 0; a < 3; ++a) t.box.push_back(box[a]);
    for (std::size_t i = 0; i < t.particles; ++i) {
      const Quat& x = q[f][i];
      t.orientation.insert(t.orientation.end(), {x.w(), x.x(), x.y(), x.z()});
      const Vec3 r = pos.empty() ? Vec3::Zero() : pos[f][i];
      t.position.insert(t.position.end(), {r.x(), r.y(), r.z()});
    }
  }
  t.species.assign(t.particles, 0);
  for (std::size_t i = 0; i < t.particles; ++i) t.id.push_back(static_cast<std::int64_t>(i));
  t.species_table = {Species{"C", Shape::cuboid(1, 1, 1), 1.0, Vec3::Ones(), Vec3::Ones()}};
  return t;
}

std::vector<std::vector<Quat>> random_frames(std::size_t frames, std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::vector<std::vector<Quat>> q(frames, std::vector<Quat>(n));
  for (auto& f : q)
    for (auto& x : f) x = random_rotation(rng);
  return q;
}

/// A rotation about z by phi.
Quat about_z(double phi) { return Quat(Eigen::AngleAxisd(phi, Vec3::UnitZ())); }

}  // namespace

TEST(OrderParameters, IsotropicConstantsMatchTheSpec) {
  EXPECT_NEAR(kCubeIsotropicMaxCos2, 0.700886, 5e-7);
  EXPECT_NEAR(kCubeIsotropicP2, 0.551329, 5e-7);
  // S_i is 0 at the isotropic value of max cos² by construction of its normalisation
  EXPECT_NEAR((M_PI * (3 * kCubeIsotropicMaxCos2 - 1) - 2 * std::sqrt(3.0)) / (2 * M_PI - 2 * std::sqrt(3.0)), 0.0, 1e-14);
}

TEST(OrderParameters, RandomOrientationsSitAtTheFiniteNBaseline) {
  const std::size_t n = 100, frames = 2000;
  const auto q = random_frames(frames, n, 2024);
  OrderSettings s;
  s.field_direction = Vec3(1, 2, 2).normalized();
  std::array<std::vector<double>, 3> u;
  std::vector<double> b2, cube, cos2, rod_trace_dev;
  for (const auto& f : q) {
    const FrameOrder o = frame_order(to_matrices(f), s, 2);
    for (std::size_t k = 0; k < 3; ++k) u[k].push_back(o.axis[k].order);
    b2.push_back(o.biaxial);
    cube.push_back(o.cube.total);
    cos2.push_back(o.cube.max_cos2);
    rod_trace_dev.push_back(std::abs(o.rod_tensor.trace() - 1.0));
    EXPECT_NEAR(o.rod_order, (2 * o.axis[2].order + 1) / 3, 1e-12);  // S = (2Q + I)/3 for the same axis
  }
  // independent Monte Carlo of the largest eigenvalue for N random unit vectors
  std::mt19937_64 rng(99);
  std::normal_distribution<double> g(0, 1);
  std::vector<double> ref;
  for (int m = 0; m < 2000; ++m) {
    Mat3 qm = Mat3::Zero();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 e = Vec3(g(rng), g(rng), g(rng)).normalized();
      qm += (3 * e * e.transpose() - Mat3::Identity()) / (2.0 * n);
    }
    ref.push_back(largest_eigenvalue_closed_form(qm));
  }
  const MeanSe r = mean_se(ref);
  EXPECT_GT(r.mean, 0.5 / std::sqrt(n));  // O(N^-1/2), clearly above 0
  EXPECT_LT(r.mean, 3.0 / std::sqrt(n));
  for (std::size_t k = 0; k < 3; ++k) {
    const MeanSe m = mean_se(u[k]);
    EXPECT_NEAR(m.mean, r.mean, 4 * std::hypot(m.se, r.se)) << "axis " << k;
  }
  // the engine's baseline (200 sets): its SE is sd/√200 with the reference's sd
  const double sd = r.se * std::sqrt(2000.0);
  EXPECT_NEAR(isotropic_order_baseline(n), r.mean, 4 * std::hypot(sd / std::sqrt(200.0), r.se));
  const MeanSe c = mean_se(cube), c2 = mean_se(cos2);
  EXPECT_NEAR(c.mean, 0.0, 4 * c.se);
  EXPECT_NEAR(c2.mean, kCubeIsotropicMaxCos2, 4 * c2.se);
  EXPECT_LT(*std::max_element(rod_trace_dev.begin(), rod_trace_dev.end()), 1e-12);
  std::printf("random N=%zu: <U_L> = %.5f +- %.5f, MC reference %.5f +- %.5f; <S_i> = %.5f +- %.5f; <max cos2> = %.5f +- %.5f\n", n,
              mean_se(u[2]).mean, mean_se(u[2]).se, r.mean, r.se, c.mean, c.se, c2.mean, c2.se);
}

TEST(OrderParameters, PerfectAlignmentGivesOneEverywhere) {
  std::mt19937_64 rng(5);
  const Quat base = random_rotation(rng);
  // head–tail flips (180° about a body axis) leave every Q^{kk} and S_i unchanged
  std::vector<Quat> q;
  const Quat flips[4] = {Quat::Identity(), Quat(0, 1, 0, 0), Quat(0, 0, 1, 0), Quat(0, 0, 0, 1)};
  for (int i = 0; i < 64; ++i) q.push_back(base * flips[i % 4]);
  const Mat3 r0 = base.toRotationMatrix();
  for (int field_axis = 0; field_axis < 3; ++field_axis) {
    OrderSettings s;
    s.field_direction = r0.col(field_axis);
    for (int K = 0; K < 3; ++K) {
      const FrameOrder o = frame_order(to_matrices(q), s, K);
      for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_NEAR(o.axis[k].order, 1.0, 1e-12);
        EXPECT_NEAR(std::abs(o.axis[k].director.dot(r0.col(static_cast<int>(k)))), 1.0, 1e-12);
      }
      EXPECT_NEAR(o.biaxial, 1.0, 1e-12) << "K=" << K;
      EXPECT_NEAR(o.rod_order, 1.0, 1e-12);
      EXPECT_NEAR(o.cube.total, 1.0, 1e-12);
      EXPECT_NEAR(o.cube.max_cos2, 1.0, 1e-12);
    }
  }
}

TEST(OrderParameters, BiaxialOrderOfExactMixturesIsTwoPMinusOne) {
  // L along z for everyone; a fraction p has W along x, the rest W along y (rotated 90° about z):
  // Q^{WW} = diag((3p−1)/2, (2−3p)/2, −1/2), Q^{TT} swapped, so B_2,L = |2p − 1| exactly.
  const std::size_t n = 200;
  for (std::size_t m : {0u, 30u, 100u, 150u, 200u}) {
    std::vector<Quat> q;
    for (std::size_t i = 0; i < n; ++i) q.push_back(i < m ? Quat::Identity() : about_z(M_PI / 2));
    const FrameOrder o = frame_order(to_matrices(q), OrderSettings{}, 2);
    const double p = static_cast<double>(m) / n;
    EXPECT_NEAR(o.biaxial, std::abs(2 * p - 1), 1e-12) << "p=" << p;
    EXPECT_NEAR(o.axis[2].order, 1.0, 1e-12);
  }
  // uniform rotation about the director: uniaxial, B_2 = 0 exactly (Q^{WW} = Q^{TT} = diag(1/4, 1/4, −1/2))
  std::vector<Quat> q;
  for (std::size_t i = 0; i < n; ++i) q.push_back(about_z(2 * M_PI * static_cast<double>(i) / n));
  const FrameOrder o = frame_order(to_matrices(q), OrderSettings{}, 2);
  EXPECT_NEAR(o.biaxial, 0.0, 1e-12);
  EXPECT_NEAR(o.axis[0].order, 0.25, 1e-12);
  EXPECT_EQ(o.nematic_axis, 2);
}

TEST(OrderParameters, DipolarChainRuleBondsHeadToTailPairsAcrossTheBoundary) {
  const Box box(Vec3(10, 10, 10));
  const DipolarBondRule rule{13.0, 1.0, -3.20, Vec3::UnitZ()};  // bonds along the field up to r = (13/3.2)^{1/3} = 1.5956
  const std::vector<Vec3> pos{
      {1, 1, 1},   {1, 1, 2.5},      // along the field, r = 1.5: βu = −13/1.5³ = −3.85 → bond
      {5, 5, 5},   {6, 5, 5},        // side by side, βu = +6.5 → no bond
      {3, 7, 9.8}, {3, 7, 0.4},      // along the field across the boundary, r = 0.6 → bond
      {8, 2, 3},   {8, 2, 4.7},      // along the field, r = 1.7: βu = −2.65 → no bond
      {3, 7, 1.5}};                  // continues the boundary chain, r = 1.1 from (3,7,0.4)
  const auto mask = dipolar_chain_mask(pos, box, rule);
  const std::vector<char> expected{1, 1, 0, 0, 1, 1, 0, 0, 1};
  EXPECT_EQ(mask, expected);
  const auto label = dipolar_clusters(pos, box, rule).label;
  EXPECT_EQ(label[4], label[8]);
  EXPECT_NE(label[0], label[4]);
  // S^(c) over the chain members (aligned, S = 1) and S^(free) over the rest (45° about x)
  std::vector<Mat3> rot(pos.size(), Mat3::Identity());
  const Mat3 tilted = Eigen::AngleAxisd(M_PI / 4, Vec3::UnitX()).toRotationMatrix();
  for (std::size_t i = 0; i < pos.size(); ++i)
    if (!mask[i]) rot[i] = tilted;
  const CubeOrder c = cube_order_average(rot, rule.field, mask);
  const double s_tilted = (M_PI * (3 * 0.5 - 1) - 2 * std::sqrt(3.0)) / (2 * M_PI - 2 * std::sqrt(3.0));
  EXPECT_NEAR(c.chain, 1.0, 1e-12);
  EXPECT_NEAR(c.free, s_tilted, 1e-12);
  EXPECT_NEAR(c.total, (5 * 1.0 + 4 * s_tilted) / 9, 1e-12);
  EXPECT_NEAR(c.chain_fraction, 5.0 / 9.0, 1e-15);
}

TEST(OrderStage, ReplicasOnTheCommonGridWithRunAveragesAndVerdict) {
  // Two replicas with slightly different time stamps; replica A aligned (U = 1), replica B
  // has U_L = 1 and B_2 = |2p − 1| with p = 3/4 in every frame: the run averages are exact.
  const std::size_t frames = 40, n = 40;
  std::vector<std::vector<Quat>> qa(frames, std::vector<Quat>(n, Quat::Identity())), qb = qa;
  for (auto& f : qb)
    for (std::size_t i = 0; i < n; ++i) f[i] = i < 3 * n / 4 ? Quat::Identity() : about_z(M_PI / 2);
  std::vector<double> ta, tb, grid;
  for (std::size_t f = 0; f < frames; ++f) {
    ta.push_back(0.1 * f);
    tb.push_back(0.1 * f * 1.02);
    grid.push_back(0.5 * (ta.back() + tb.back()));
  }
  OrderStageSettings s;
  s.order.main_axis = 2;  // B_2,L (with "auto" the all-aligned first replica would tie all three axes)
  OrderAnalysis a(s);
  a.accumulate(make_trajectory(qa, ta), -1);
  a.accumulate(make_trajectory(qb, tb), -1);
  const OrderResult r = a.compute(grid);
  EXPECT_EQ(r.time, grid);
  EXPECT_EQ(r.replicas, 2u);
  EXPECT_TRUE(r.nematic);
  EXPECT_NEAR(r.get("U_L").run_average.value, 1.0, 1e-12);
  EXPECT_NEAR(r.get("B2").run_average.value, 0.75, 1e-12);
  EXPECT_NEAR(r.get("B2").run_average.error, 0.25, 1e-12);  // SE of {1, 0.5}
  for (std::size_t f = 0; f < frames; ++f) EXPECT_NEAR(r.get("B2").mean[f], 0.75, 1e-12);
  EXPECT_NEAR(r.isotropic_baseline, isotropic_order_baseline(n), 1e-15);
}

TEST(OrderStage, RandomReplicaIsIsotropicAndAutoAxisRecorded) {
  const auto q = random_frames(50, 300, 11);
  OrderStageSettings s;
  OrderAnalysis a(s);
  const Trajectory t = make_trajectory(q, anisodyn::testing_support::linear_times(50, 1.0));
  a.accumulate(t, -1);
  const OrderResult r = a.compute(t.time);
  EXPECT_FALSE(r.nematic);
  EXPECT_LT(r.largest_eigenvalue, kNematicThreshold);
  // one replica: block-average error; U sits at the baseline within 4 combined errors (the
  // baseline averages 200 independent sets, so its SE is the per-frame sd/√200 = error·√(50/200))
  const auto& u = r.get("U_L").run_average;
  EXPECT_GT(u.error, 0.0);
  EXPECT_NEAR(u.value, r.isotropic_baseline, 4 * u.error * std::sqrt(1.0 + 50.0 / 200.0));
  EXPECT_GE(r.main_axis, 0);
  EXPECT_TRUE(std::isnan(r.get("U_L").error[0]));  // no replica SE with one replica
}

TEST(OrderStage, ChainSplitFromPositions) {
  // 4 cubes: two bonded along the field (aligned), two far apart (tilted 45° about x)
  const std::vector<Vec3> p{{1, 1, 1}, {1, 1, 2.2}, {5, 5, 5}, {8, 1, 5}};
  const Quat tilt(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitX()));
  std::vector<std::vector<Quat>> q(3, {Quat::Identity(), Quat::Identity(), tilt, tilt});
  std::vector<std::vector<Vec3>> pos(3, p);
  OrderStageSettings s;
  s.order.chains = DipolarBondRule{13.0, 1.0, -3.2, Vec3::UnitZ()};
  OrderAnalysis a(s);
  a.accumulate(make_trajectory(q, {0, 1, 2}, pos), -1);
  const OrderResult r = a.compute({0, 1, 2});
  const double s_tilted = (M_PI * 0.5 - 2 * std::sqrt(3.0)) / (2 * M_PI - 2 * std::sqrt(3.0));
  EXPECT_NEAR(r.get("S_cube_chain").run_average.value, 1.0, 1e-12);
  EXPECT_NEAR(r.get("S_cube_free").run_average.value, s_tilted, 1e-12);
  EXPECT_NEAR(r.get("chain_fraction").run_average.value, 0.5, 1e-12);
}

TEST(OrderStage, BadInputsAreInputErrors) {
  nlohmann::json j = {{"observables", {"U", "Q6"}}};
  tool::ConfigNode cfg(j, "order.json");
  const InputError e = input_error([&] { parse_order_settings(cfg); });
  EXPECT_NE(std::string(e.what()).find("observables"), std::string::npos);
  nlohmann::json j2 = {{"chain_threshold", {{"gamma", 13}, {"bu_max", 1.0}}}};
  tool::ConfigNode cfg2(j2, "order.json");
  input_error([&] { parse_order_settings(cfg2); });
  OrderStageSettings s;
  s.average_from = 100.0;  // after the last frame
  OrderAnalysis a(s, "order.json");
  const auto q = random_frames(5, 10, 1);
  a.accumulate(make_trajectory(q, {0, 1, 2, 3, 4}), -1);
  const InputError e3 = input_error([&] { a.compute({0, 1, 2, 3, 4}); });
  EXPECT_EQ(e3.json_path(), "average_from");
}

class OrderFileTest : public anisodyn::testing_support::ScratchDirTest {
 protected:
  OrderFileTest() : ScratchDirTest("order") {}
};

TEST_F(OrderFileTest, QuaternionConventionThroughH5md) {
  // Written through the engine's H5MD writer: body axis k of a particle with rotation R lies along
  // R.col(k) in the lab (a transposed or conjugated reading would give the rows instead).
  std::mt19937_64 rng(8);
  const Quat q = random_rotation(rng);
  const Mat3 r = q.toRotationMatrix();
  anisodyn::testing_support::SyntheticTrajectory st;
  st.time = {0.0, 1.0};
  st.position.assign(2, std::vector<Vec3>(5, Vec3(1, 1, 1)));
  st.orientation.assign(2, std::vector<Quat>(5, q));
  st.table = {Species{"C", Shape::cuboid(1, 1, 1), 1.0, Vec3::Ones(), Vec3::Ones()}};
  const std::string path = file("q.h5");
  st.write(path);
  TrajectoryNeeds needs;
  needs.orientations = true;
  const Trajectory t = load_trajectory(path, needs);
  OrderSettings s;
  s.field_direction = r.col(0);
  const FrameOrder o = trajectory_frame_order(t, 1, t.members(-1), s, 2);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(std::abs(o.axis[static_cast<std::size_t>(k)].director.dot(r.col(k))), 1.0, 1e-9);
  EXPECT_NEAR(o.cube.total, 1.0, 1e-9);
  const auto sel = select_oriented_species(path, "", "cfg.json", "species");
  ASSERT_EQ(sel.size(), 1u);
  EXPECT_EQ(sel[0].name, "C");
}

TEST_F(OrderFileTest, SpheresAreNotOrientedSpecies) {
  anisodyn::testing_support::SyntheticTrajectory st;
  st.time = {0.0, 1.0};
  st.position.assign(2, std::vector<Vec3>(4, Vec3(1, 1, 1)));
  st.species = {0, 1, 0, 1};
  st.table = {Species{"S", Shape::sphere(1.0), 1.0, Vec3::Ones(), Vec3::Ones()},
              Species{"C", Shape::cuboid(1, 1, 1), 1.0, Vec3::Ones(), Vec3::Ones()}};
  const std::string path = file("mix.h5");
  st.write(path);
  const auto sel = select_oriented_species(path, "", "cfg.json", "species");
  ASSERT_EQ(sel.size(), 1u);
  EXPECT_EQ(sel[0].name, "C");
  EXPECT_EQ(sel[0].index, 1);
  const InputError e = input_error([&] { select_oriented_species(path, "S", "cfg.json", "species"); });
  EXPECT_EQ(e.json_path(), "species");
  // the scopes of the per-species stages: every species, the anisotropic ones, exactly one
  EXPECT_EQ(select_species(path, SpeciesRequest{"", SpeciesScope::Every}, "cfg.json", "species").size(), 2u);
  EXPECT_EQ(select_species(path, SpeciesRequest{"", SpeciesScope::Oriented}, "cfg.json", "species").size(), 1u);
  const auto one = select_species(path, SpeciesRequest{"S", SpeciesScope::Single}, "cfg.json", "species");
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].index, 0);
  const InputError several = input_error([&] { select_species(path, SpeciesRequest{"", SpeciesScope::Single}, "cfg.json", "species"); });
  EXPECT_EQ(several.json_path(), "species");
}

TEST_F(OrderFileTest, AWindowKeepsTrajectoryTimeOnTheCommonGrid) {
  // aligned boards for t < 5, then half of them turned: U_L drops from 1; the window 3 … 6 holds
  // both, on the trajectory's own time axis
  anisodyn::testing_support::SyntheticTrajectory st;
  st.time = anisodyn::testing_support::linear_times(10, 1.0);
  st.position.assign(10, std::vector<Vec3>(8, Vec3(1, 1, 1)));
  st.orientation.assign(10, std::vector<Quat>(8, Quat::Identity()));
  for (std::size_t f = 5; f < 10; ++f)
    for (std::size_t i = 0; i < 4; ++i) st.orientation[f][i] = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()));
  st.table = {Species{"C", Shape::cuboid(1, 2, 8), 1.0, Vec3::Ones(), Vec3::Ones()}};
  const std::string path = file("turn.h5");
  st.write(path);
  TrajectoryNeeds needs;
  needs.orientations = true;
  needs.window = anisodyn::testing_support::time_window(3.0, 6.0);
  OrderAnalysis a(OrderStageSettings{}, "order.json");
  const auto grid = for_each_replica({path}, needs, [&](const Trajectory& t, std::size_t) { a.accumulate(t, -1); });
  const OrderResult r = a.compute(grid);
  EXPECT_EQ(r.time, (std::vector<double>{3, 4, 5, 6}));
  EXPECT_EQ(r.averaged_frames, 4u);
  const auto& u = r.get("U_L").mean;
  EXPECT_NEAR(u[0], 1.0, 1e-12);
  EXPECT_LT(u[2], 0.9);  // t = 5: half turned
}

// Pair structure (spec 50 §4, §1.7) on configurations with exact answers: an ideal gas (g, g_∥, g_⊥
// at their exact expectation (N − 1)/N for like pairs and 1 for unlike pairs, slab profiles 1),
// a simple cubic lattice (shells at a, a√2, a√3 with coordination numbers 6, 12, 8; on-axis and
// in-plane neighbours for g_∥, g_⊥ about a director), and the bad inputs (a director in an
// isotropic box, r_max beyond half the box, unknown species).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "anisodyn/analysis/pair_structure.hpp"
#include "anisodyn/core/error.hpp"
#include "input_error.hpp"
#include "scratch_dir.hpp"
#include "synthetic_trajectory.hpp"
#include "time_window.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;
using anisodyn::testing_support::input_error;

namespace {

/// In-memory trajectory: positions [frame][particle], one orientation for everyone, species per particle.
Trajectory make_trajectory(const std::vector<std::vector<Vec3>>& pos, const Vec3& box, const std::vector<int>& species,
                           const SpeciesTable& table, const Quat& q = Quat::Identity(),
                           const std::vector<std::vector<Quat>>& orientations = {}) {
  Trajectory t;
  t.path = "memory";
  t.frames = pos.size();
  t.particles = pos.front().size();
  for (std::size_t f = 0; f < t.frames; ++f) {
    t.time.push_back(static_cast<double>(f));
    t.step.push_back(static_cast<std::int64_t>(f));
    for (int a = 0; a < 3; ++a) t.box.push_back(box[a]);
    for (std::size_t i = 0; i < t.particles; ++i) {
      const Quat x = orientations.empty() ? q : orientations[f][i];
      t.position.insert(t.position.end(), {pos[f][i].x(), pos[f][i].y(), pos[f][i].z()});
      t.orientation.insert(t.orientation.end(), {x.w(), x.x(), x.y(), x.z()});
    }
  }
  t.species = species.empty() ? std::vector<int>(t.particles, 0) : species;
  for (std::size_t i = 0; i < t.particles; ++i) t.id.push_back(static_cast<std::int64_t>(i));
  t.species_table = table;
  return t;
}

const SpeciesTable kOne{Species{"A", Shape::cuboid(1, 1, 1), 1.0, Vec3::Ones(), Vec3::Ones()}};
const SpeciesTable kTwo{Species{"A", Shape::cuboid(1, 1, 1), 1.0, Vec3::Ones(), Vec3::Ones()},
                        Species{"B", Shape::sphere(1.0), 1.0, Vec3::Ones(), Vec3::Ones()}};

std::vector<std::vector<Vec3>> uniform_gas(std::size_t frames, std::size_t n, const Vec3& box, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<std::vector<Vec3>> p(frames, std::vector<Vec3>(n));
  // unwrapped coordinates anywhere: the analysis must wrap them (slabs) and take minimum images (pairs)
  for (auto& f : p)
    for (auto& r : f) r = Vec3(u(rng) * box.x() * 3 - box.x(), u(rng) * box.y(), u(rng) * box.z() + 2 * box.z());
  return p;
}

/// Simple cubic lattice of n³ sites with spacing a.
std::vector<Vec3> cubic_lattice(int n, double a) {
  std::vector<Vec3> p;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) p.emplace_back(i * a, j * a, k * a);
  return p;
}

void expect_curve_near(const std::vector<double>& v, const std::vector<double>& se, double expected, const char* what,
                       std::size_t* checked = nullptr) {
  double worst = 0;
  for (std::size_t b = 0; b < v.size(); ++b) {
    if (std::isnan(v[b])) continue;  // outside the minimum-image cell
    EXPECT_NEAR(v[b], expected, 4 * se[b]) << what << " bin " << b;
    worst = std::max(worst, std::abs(v[b] - expected) / se[b]);
    if (checked) ++*checked;
  }
  std::printf("%s: largest |value - %.5f| = %.2f SE\n", what, expected, worst);
}

}  // namespace

TEST(PairStructure, IdealGasIsUniformInEveryBin) {
  const Vec3 box(6, 6, 6);
  const std::size_t n = 400, replicas = 30;
  std::mt19937_64 rng(17);
  PairStructureSettings s;
  s.dr = 0.1;
  s.direction = Vec3(1, 1, 0).normalized();
  PairStructureAnalysis a(s, replicas);
  for (std::size_t r = 0; r < replicas; ++r) a.accumulate(make_trajectory(uniform_gas(60, n, box, rng), box, {}, kOne));
  const PairStructureResult res = a.compute();
  ASSERT_EQ(res.pairs.size(), 1u);
  ASSERT_EQ(res.r.size(), 30u);
  EXPECT_EQ(res.samples, replicas);
  const auto& c = res.pairs[0];
  const double expected = (n - 1.0) / n;  // Σ_i Σ_{j≠i} over N ρ v: exact for N uniform particles
  std::size_t par = 0, perp = 0;
  expect_curve_near(c.g, c.g_se, expected, "g");
  expect_curve_near(c.g_par, c.g_par_se, expected, "g_par", &par);
  expect_curve_near(c.g_perp, c.g_perp_se, expected, "g_perp", &perp);
  EXPECT_GE(par, 29u);   // bins whose cylinder fits: (r + dr)² + R² ≤ (L/2)²
  EXPECT_GE(perp, 29u);
  ASSERT_EQ(res.profiles.size(), 1u);
  for (int ax = 0; ax < 3; ++ax) {
    ASSERT_EQ(res.profiles[0].rho[ax].size(), 50u);
    expect_curve_near(res.profiles[0].rho[ax], res.profiles[0].rho_se[ax], 1.0, "slab");
    EXPECT_NEAR(res.profiles[0].s[ax][0], 0.06, 1e-12);  // first slab centre: L/100
  }
}

TEST(PairStructure, UnlikeSpeciesIdealGasIsOneAndSymmetric) {
  const Vec3 box(6, 6, 6);
  const std::size_t n = 300, replicas = 20;
  std::vector<int> species(n);
  for (std::size_t i = 0; i < n; ++i) species[i] = i % 3 == 0 ? 1 : 0;  // 100 B, 200 A
  std::mt19937_64 rng(23);
  PairStructureSettings s;
  s.dr = 0.15;
  s.reference = PairReference::None;
  s.pairs = {{"A", "B"}, {"B", "A"}};
  PairStructureAnalysis a(s, replicas);
  for (std::size_t r = 0; r < replicas; ++r) a.accumulate(make_trajectory(uniform_gas(60, n, box, rng), box, species, kTwo));
  const PairStructureResult res = a.compute();
  ASSERT_EQ(res.pairs.size(), 2u);
  EXPECT_EQ(res.pairs[0].count_a, 200u);
  EXPECT_EQ(res.pairs[0].count_b, 100u);
  expect_curve_near(res.pairs[0].g, res.pairs[0].g_se, 1.0, "g_AB");
  for (std::size_t b = 0; b < res.r.size(); ++b) {
    EXPECT_NEAR(res.pairs[0].g[b], res.pairs[1].g[b], 1e-12 * (1 + res.pairs[0].g[b]));  // N_A ρ_B = N_B ρ_A
    EXPECT_TRUE(std::isnan(res.pairs[0].g_par[b]));  // no reference requested
  }
  EXPECT_EQ(res.profiles.size(), 2u);
}

TEST(PairStructure, SimpleCubicLatticeShellsAndCoordinationNumbers) {
  const double a = 1.02;  // bins of 0.05 hold a, a√2, a√3, 2a well inside (no edge round-off)
  const int n = 8;
  const Vec3 box = Vec3::Constant(n * a);
  // director reference: every particle's L axis along x (90° about y)
  const Quat q(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitY()));
  PairStructureSettings s;
  s.reference = PairReference::Director;
  s.axis = 2;
  PairStructureAnalysis an(s, 1);
  an.accumulate(make_trajectory({cubic_lattice(n, a)}, box, {}, kOne, q));
  const PairStructureResult r = an.compute();
  ASSERT_EQ(r.director_axis.size(), 1u);
  EXPECT_NEAR(r.director_order[0], 1.0, 1e-12);
  const auto& c = r.pairs[0];
  const double rho = std::pow(n, 3) / box.prod(), dr = s.dr;
  auto bin = [&](double x) { return static_cast<std::size_t>(x / dr); };
  auto shell = [&](std::size_t b) {  // N ρ v(r) g / N = neighbours in the bin
    const double r0 = b * dr, r1 = r0 + dr;
    return rho * 4 * M_PI * (r1 * r1 * r1 - r0 * r0 * r0) / 3 * c.g[b];
  };
  const std::size_t b1 = bin(a), b2 = bin(a * std::sqrt(2.0)), b3 = bin(a * std::sqrt(3.0)), b4 = bin(2 * a);
  for (std::size_t b = 0; b < b4; ++b) {
    const double expected = b == b1 ? 6 : b == b2 ? 12 : b == b3 ? 8 : 0;
    EXPECT_NEAR(shell(b), expected, 1e-9) << "bin " << b << " r = " << r.r[b];
  }
  EXPECT_NEAR(shell(b4), 6, 1e-9);
  EXPECT_NEAR(c.coordination[b1], 6, 1e-9);
  EXPECT_NEAR(c.coordination[b3], 26, 1e-9);
  EXPECT_NEAR(c.coordination[b4], 32, 1e-9);
  // g_∥ about the director (x): the on-axis neighbours at ±a, ±2a, ±3a (2 each) in a cylinder R = 0.5
  auto par = [&](std::size_t b) { return rho * 2 * M_PI * s.cylinder_radius * s.cylinder_radius * dr * c.g_par[b]; };
  EXPECT_NEAR(par(b1), 2, 1e-9);
  EXPECT_NEAR(par(bin(2 * a)), 2, 1e-9);
  EXPECT_NEAR(par(bin(3 * a)), 2, 1e-9);
  EXPECT_NEAR(par(bin(0.5 * a)), 0, 1e-12);
  // g_⊥: in-plane neighbours (|x| < h = 0.5) at a (4), a√2 (4), 2a (4)
  auto perp = [&](std::size_t b) {
    const double r0 = b * dr, r1 = r0 + dr;
    return rho * M_PI * (r1 * r1 - r0 * r0) * 2 * s.slab_half_height * c.g_perp[b];
  };
  EXPECT_NEAR(perp(b1), 4, 1e-9);
  EXPECT_NEAR(perp(b2), 4, 1e-9);
  EXPECT_NEAR(perp(b4), 4, 1e-9);
  EXPECT_NEAR(perp(b3), 0, 1e-12);
}

class PairStructureFileTest : public anisodyn::testing_support::ScratchDirTest {
 protected:
  PairStructureFileTest() : ScratchDirTest("structure") {}
};

TEST_F(PairStructureFileTest, TimeWindowWithStrideAndSingleReplicaBlocks) {
  const Vec3 box(5, 5, 5);
  std::mt19937_64 rng(3);
  anisodyn::testing_support::SyntheticTrajectory syn;
  syn.box = box;
  syn.time = anisodyn::testing_support::linear_times(60, 0.5);
  syn.position = uniform_gas(60, 100, box, rng);
  syn.table = kOne;
  const std::string path = file("gas.h5");
  syn.write(path);
  TrajectoryNeeds needs;
  needs.positions = true;
  needs.window = anisodyn::testing_support::time_window(1.0, std::nullopt, 3);  // frames 2, 5, …, 59: 20 frames in 10 blocks
  PairStructureAnalysis a(PairStructureSettings{}, 1);
  for_each_replica({path}, needs, [&](const Trajectory& t, std::size_t) { a.accumulate(t); });
  const auto r = a.compute();
  EXPECT_EQ(r.frames_per_replica, 20u);
  EXPECT_EQ(r.samples, 10u);
  EXPECT_TRUE(r.blocks);
  // the old frame-index key is refused with a pointer to the window
  nlohmann::json j = {{"frames", {{"first", 2}}}};
  tool::ConfigNode cfg(j, "structure.json");
  EXPECT_EQ(input_error([&] { parse_structure_settings(cfg); }).json_path(), "frames");
}

TEST(PairStructure, DirectorInAnIsotropicBoxIsAnInputError) {
  const Vec3 box(6, 6, 6);
  std::mt19937_64 rng(4);
  std::normal_distribution<double> g(0, 1);
  std::vector<std::vector<Quat>> q(5, std::vector<Quat>(200));
  for (auto& f : q)
    for (auto& x : f) x = Quat(g(rng), g(rng), g(rng), g(rng)).normalized();
  PairStructureSettings s;
  s.reference = PairReference::Director;
  PairStructureAnalysis a(s, 1, "structure.json");
  const Trajectory t = make_trajectory(uniform_gas(5, 200, box, rng), box, {}, kOne, Quat::Identity(), q);
  const InputError e = input_error([&] { a.accumulate(t); });
  EXPECT_EQ(e.json_path(), "reference");
  EXPECT_NE(std::string(e.what()).find("no orientational order"), std::string::npos);
}

TEST(PairStructure, BadParametersAreInputErrors) {
  const Vec3 box(6, 6, 6);
  std::mt19937_64 rng(5);
  const Trajectory t = make_trajectory(uniform_gas(2, 20, box, rng), box, {}, kOne);
  PairStructureSettings s;
  s.r_max = 3.5;
  PairStructureAnalysis a(s, 1, "structure.json");
  EXPECT_EQ(input_error([&] { a.accumulate(t); }).json_path(), "r_max");
  PairStructureSettings s2;
  s2.pairs = {{"A", "Q"}};
  PairStructureAnalysis b(s2, 1, "structure.json");
  EXPECT_EQ(input_error([&] { b.accumulate(t); }).json_path(), "pairs[0]");
  PairStructureSettings s3;
  s3.reference = PairReference::Director;
  s3.director_species = "B";  // a sphere
  PairStructureAnalysis c(s3, 1, "structure.json");
  const Trajectory two = make_trajectory(uniform_gas(2, 20, box, rng), box, std::vector<int>(20, 1), kTwo);
  EXPECT_EQ(input_error([&] { c.accumulate(two); }).json_path(), "director_species");
  nlohmann::json j = {{"pairs", {"A", "B"}}};
  tool::ConfigNode cfg(j, "structure.json");
  EXPECT_EQ(input_error([&] { parse_structure_settings(cfg); }).json_path(), "pairs");
  nlohmann::json j2 = {{"frames", {{"first", 5}, {"last", 2}}}};
  tool::ConfigNode cfg2(j2, "structure.json");
  input_error([&] { parse_structure_settings(cfg2); });
}

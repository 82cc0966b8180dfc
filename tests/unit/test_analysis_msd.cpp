// MSD stage on synthetic data with known answers: Gaussian walks with anisotropic D (MSD = 2 D_a t
// per axis, D fit, NGP = 0, β = 1, D_tot = (D_par + 2 D_perp)/3), a walk with a non-Gaussian
// jump law (NGP closed form), and the body-frame components.
#include <gtest/gtest.h>

#include "anisodyn/analysis/msd.hpp"
#include "anisodyn/core/error.hpp"
#include "input_error.hpp"
#include "scratch_dir.hpp"
#include "synthetic_trajectory.hpp"
#include "time_window.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;
using anisodyn::testing_support::frames_of;
using anisodyn::testing_support::gaussian_walks;
using anisodyn::testing_support::input_error;
using anisodyn::testing_support::linear_times;

namespace {

class MsdTest : public anisodyn::testing_support::ScratchDirTest {
 protected:
  MsdTest() : ScratchDirTest("msd") {}

  MsdResult run(const std::vector<std::string>& paths, MsdSettings s, const FrameWindow& window = {}, int species = -1) {
    MsdAnalysis a(s, paths.size(), "msd.json");
    TrajectoryNeeds needs;
    needs.positions = true;
    needs.orientations = true;
    needs.window = window;
    for_each_replica(paths, needs, [&](const Trajectory& t, std::size_t) { a.accumulate(t, species); });
    return a.compute();
  }
};

TEST_F(MsdTest, GaussianWalksGiveLinearMsdPerAxisAndZeroNgp) {
  const Vec3 D(0.5, 0.5, 2.0);
  std::vector<std::string> paths;
  for (unsigned r = 0; r < 10; ++r) {
    paths.push_back(file("walk" + std::to_string(r) + ".h5"));
    gaussian_walks(200, linear_times(201, 0.1), D, 100 + r, Vec3(5, 6, 7)).write(paths.back());
  }
  MsdSettings s;
  s.reference = MsdReference::Vector;
  s.direction = Vec3::UnitZ();
  const MsdResult r = run(paths, s);
  ASSERT_GT(r.lag.size(), 10u);
  EXPECT_TRUE(r.uniform_frames);
  // a few lags across the range (every lag would be many correlated comparisons at 4 σ)
  for (std::size_t c : {std::size_t{0}, r.lag.size() / 4, r.lag.size() / 2, 3 * r.lag.size() / 4}) {
    const double t = r.lag[c];
    const auto check = [&](const char* name, double expected) {
      const auto& comp = r.component(name);
      EXPECT_NEAR(comp.msd[c], expected, 4 * comp.msd_error[c] + 1e-12) << name << " t=" << t;
    };
    check("x", 2 * D.x() * t);
    check("z", 2 * D.z() * t);
    check("par", 2 * D.z() * t);
    check("perp", 2 * (D.x() + D.y()) * t);
    check("tot", 2 * D.sum() * t);
    for (const char* name : {"x", "z", "perp"}) {
      const auto& comp = r.component(name);
      EXPECT_NEAR(comp.ngp[c], 0.0, 4 * comp.ngp_error[c]) << name << " t=" << t;
    }
  }
  // the fit: D per component, D_tot = (D_par + 2 D_perp)/3 identically (spec 50 §1.3)
  const auto& par = r.component("par").diffusion;
  const auto& perp = r.component("perp").diffusion;
  const auto& tot = r.component("tot").diffusion;
  EXPECT_NEAR(par.value, D.z(), 4 * par.error);
  EXPECT_NEAR(perp.value, 0.5 * (D.x() + D.y()), 4 * perp.error);
  EXPECT_NEAR(tot.value, (par.value + 2 * perp.value) / 3, 1e-12 * tot.value);
  EXPECT_NEAR(r.fit_mean_beta, 1.0, 0.05);
}

TEST_F(MsdTest, AnisotropicNgpConstantMakesTheAnisotropicGaussianZero) {
  const Vec3 D(0.2, 0.2, 3.0);
  std::vector<std::string> paths;
  for (unsigned r = 0; r < 3; ++r) {
    paths.push_back(file("aniso" + std::to_string(r) + ".h5"));
    gaussian_walks(300, linear_times(101, 0.05), D, 7 + r).write(paths.back());
  }
  MsdSettings s;
  s.reference = MsdReference::Vector;
  s.direction = Vec3::UnitZ();
  s.ngp_constant = "anisotropic";
  const MsdResult aniso = run(paths, s);
  s.ngp_constant = "isotropic";
  const MsdResult iso = run(paths, s);
  // c'_2,3 for D_par/D_perp = 15: the isotropic 5/3 reads a spurious positive α_2
  const double dp = 3.0, dq = 0.2;
  const double c_aniso = (3 * dp * dp + 8 * dq * dq + 4 * dp * dq) / (dp * dp + 4 * dq * dq + 4 * dp * dq);
  for (std::size_t c = 0; c < aniso.lag.size(); ++c) {
    const auto& a = aniso.component("tot");
    EXPECT_NEAR(a.ngp[c], 0.0, 4 * a.ngp_error[c]);
    EXPECT_NEAR(iso.component("tot").ngp[c], c_aniso / (5.0 / 3.0) - 1.0, 4 * a.ngp_error[c] * c_aniso);
  }
}

TEST_F(MsdTest, NonGaussianJumpsMatchTheClosedFormNgp) {
  // Each frame interval every particle jumps by ±a along x with probability p, else stays:
  // after k intervals the jump count is Binomial(k, p) and
  //   <x²> = k p a²,  <x⁴> = a⁴ (k p (1 − p)(1 − 6p(1 − p))... ) — use the exact moments of a sum of
  // k iid steps s with <s²> = p a², <s⁴> = p a⁴:  <x⁴> = k <s⁴> + 3 k (k − 1) <s²>²,
  // so α_2,1 = <x⁴>/(3<x²>²) − 1 = (1/p − 3)/(3k).
  const double p = 0.1, a = 0.5;
  std::vector<std::string> paths;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  for (unsigned r = 0; r < 4; ++r) {
    auto t = gaussian_walks(500, linear_times(41, 1.0), Vec3(0, 0, 0), 1);
    for (std::size_t f = 1; f < t.time.size(); ++f)
      for (std::size_t i = 0; i < t.particles(); ++i) {
        const double x = u(rng);
        const double step = x < p / 2 ? a : x < p ? -a : 0.0;
        t.position[f][i] = t.position[f - 1][i] + Vec3(step, 0, 0);
      }
    paths.push_back(file("jumps" + std::to_string(r) + ".h5"));
    t.write(paths.back());
  }
  MsdSettings s;
  s.lags_per_decade = 0;  // every lag
  const MsdResult r = run(paths, s);
  const auto& x = r.component("x");
  for (std::size_t c = 0; c < r.lag.size(); ++c) {
    const double k = r.lag[c];
    EXPECT_NEAR(x.msd[c], k * p * a * a, 4 * x.msd_error[c]);
    EXPECT_NEAR(x.ngp[c], (1.0 / p - 3.0) / (3.0 * k), 4 * x.ngp_error[c]) << "k=" << k;
  }
}

TEST_F(MsdTest, SingleReplicaUsesOriginBlocksForErrorsAndLogFramesAreBinned) {
  // log-spaced frames: t_k = 0.01·10^(k/10); the lag classes are log bins
  std::vector<double> time{0.0};
  for (int k = 0; k <= 40; ++k) time.push_back(0.01 * std::pow(10.0, k / 10.0));
  const std::string path = file("log.h5");
  gaussian_walks(400, time, Vec3(1, 1, 1), 11).write(path);
  MsdSettings s;
  const MsdResult r = run({path}, s);
  EXPECT_FALSE(r.uniform_frames);
  EXPECT_EQ(r.samples, 10u);
  for (std::size_t c = 0; c < r.lag.size(); ++c) {
    const auto& tot = r.component("tot");
    if (std::isnan(tot.msd_error[c])) continue;
    EXPECT_NEAR(tot.msd[c], 6 * r.lag[c], 5 * tot.msd_error[c] + 1e-9 * r.lag[c]) << r.lag[c];
  }
}

TEST_F(MsdTest, AWindowGivesTheMsdOfTheTruncatedTrajectory) {
  // frames 20, 22, …, 70 of a 101-frame run (t = 2 … 7, stride 2) against files holding only them
  std::vector<std::string> full, cut;
  for (unsigned r = 0; r < 3; ++r) {
    const auto walk = gaussian_walks(50, linear_times(101, 0.1), Vec3(0.3, 0.5, 1.0), 60 + r);
    full.push_back(file("full" + std::to_string(r) + ".h5"));
    cut.push_back(file("cut" + std::to_string(r) + ".h5"));
    walk.write(full.back());
    frames_of(walk, 20, 26, 2).write(cut.back());
  }
  const FrameWindow w = anisodyn::testing_support::time_window(2.0, 7.0, 2);
  MsdSettings s;
  s.reference = MsdReference::Vector;
  s.fit_window = std::make_pair(0.4, 2.0);
  const MsdResult windowed = run(full, s, w), truncated = run(cut, s), whole = run(full, s);
  ASSERT_EQ(windowed.lag, truncated.lag);  // lags from the window's frames, not from t = 0
  EXPECT_NE(windowed.lag.size(), whole.lag.size());
  for (const char* name : {"tot", "x", "z", "par", "perp"}) {
    EXPECT_EQ(windowed.component(name).msd, truncated.component(name).msd) << name;
    EXPECT_EQ(windowed.component(name).msd_error, truncated.component(name).msd_error) << name;
    EXPECT_EQ(windowed.component(name).diffusion.value, truncated.component(name).diffusion.value) << name;
    EXPECT_TRUE(std::isfinite(windowed.component(name).diffusion.value)) << name;
  }
  EXPECT_EQ(windowed.fit_t_max, truncated.fit_t_max);
}

namespace {

const Quat kLAlongY(Eigen::AngleAxisd(-M_PI / 2, Vec3::UnitX()));  // body z (L) → lab y

/// `boards` boards with L along y (random azimuth: a uniaxial nematic) and `spheres` spheres
/// (identity orientation: every own axis perfectly "ordered", T = x the first), all diffusing with
/// D = (0.2, 2, 0.2): fast along the boards' director only.
testing_support::SyntheticTrajectory spheres_among_aligned_boards(std::size_t boards, std::size_t spheres, unsigned seed,
                                                                  bool second_board_species = false) {
  auto t = gaussian_walks(boards + spheres, linear_times(41, 0.05), Vec3(0.2, 2.0, 0.2), seed);
  t.table = {Species{"board", Shape::cuboid(1, 3, 12), 1.0, Vec3::Ones(), Vec3::Ones()},
             Species{"hs", Shape::sphere(0.1), 1.0, Vec3::Ones(), Vec3::Ones()}};
  if (second_board_species) t.table.push_back(Species{"rod", Shape::cuboid(1, 1, 8), 1.0, Vec3::Ones(), Vec3::Ones()});
  t.species.assign(boards + spheres, 1);
  for (std::size_t i = 0; i < boards; ++i) t.species[i] = second_board_species && i % 2 ? 2 : 0;
  t.orientation.assign(t.time.size(), std::vector<Quat>(boards + spheres, Quat::Identity()));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> azimuth(0.0, 2 * M_PI);
  for (std::size_t i = 0; i < boards; ++i) {
    const Quat q = kLAlongY * Quat(Eigen::AngleAxisd(azimuth(rng), Vec3::UnitZ()));
    for (auto& frame : t.orientation) frame[i] = q;
  }
  return t;
}

}  // namespace

TEST_F(MsdTest, SpheresTakeTheDirectorOfTheAnisotropicSpecies) {
  std::vector<std::string> paths;
  for (unsigned r = 0; r < 6; ++r) {
    paths.push_back(file("mix" + std::to_string(r) + ".h5"));
    spheres_among_aligned_boards(40, 200, 80 + r).write(paths.back());
  }
  MsdSettings s;
  s.reference = MsdReference::Director;
  const MsdResult r = run(paths, s, {}, 1);  // the spheres
  ASSERT_EQ(r.directors.size(), 6u);
  EXPECT_NEAR(std::abs(r.directors[0].y()), 1.0, 1e-12);  // the boards' L, not an axis of the spheres' own
  EXPECT_NEAR(r.director_order[0], 1.0, 1e-12);
  EXPECT_EQ(r.director_species, "board");
  const auto& par = r.component("par").diffusion;
  const auto& perp = r.component("perp").diffusion;
  EXPECT_NEAR(par.value, 2.0, 4 * par.error);
  EXPECT_NEAR(perp.value, 0.2, 4 * perp.error);
  EXPECT_GT(par.value, 5 * perp.value);  // about the spheres' own T (x): 0.2 and 1.1
}

TEST_F(MsdTest, DirectorSpeciesIsRequiredAmongSeveralAnisotropicSpeciesAndRefusedOtherwise) {
  const std::string two = file("two.h5"), one = file("one.h5"), none = file("none.h5");
  spheres_among_aligned_boards(20, 20, 90, true).write(two);
  spheres_among_aligned_boards(20, 20, 91).write(one);
  auto spheres_only = gaussian_walks(20, linear_times(11, 0.1), Vec3(1, 1, 1), 92);
  spheres_only.write(none);
  MsdSettings s;
  s.reference = MsdReference::Director;
  EXPECT_EQ(input_error([&] { run({two}, s, {}, 1); }).json_path(), "director_species");
  s.director_species = "rod";
  const MsdResult r = run({two}, s, {}, 1);
  EXPECT_EQ(r.director_species, "rod");
  EXPECT_NEAR(std::abs(r.directors[0].y()), 1.0, 1e-12);
  // named for the boards themselves: they are their own reference
  const InputError own = input_error([&] { run({one}, s, {}, 0); });
  EXPECT_EQ(own.json_path(), "director_species");
  EXPECT_EQ(own.file(), "msd.json");
  s.director_species = "hs";
  EXPECT_EQ(input_error([&] { run({one}, s, {}, 1); }).json_path(), "director_species");
  s.director_species.clear();
  EXPECT_EQ(input_error([&] { run({none}, s, {}, 0); }).json_path(), "reference");
  // the key without the director reference has no effect: refused
  nlohmann::json j = {{"reference", "axes"}, {"director_species", "board"}};
  io::ConfigNode cfg(j, "msd.json");
  EXPECT_EQ(input_error([&] { parse_msd_settings(cfg); }).json_path(), "director_species");
}

}  // namespace

// MSD stage on synthetic data with known answers: Gaussian walks with anisotropic D (MSD = 2 D_a t
// per axis, D fit, NGP = 0 with the isotropic and the anisotropic constant, β = 1,
// D_tot = (D_par + 2 D_perp)/3), a walk with a non-Gaussian jump law (NGP closed form), a single
// replica on log-spaced frames (origin blocks), and the per-sample curves behind MSD and error.
//
// Every comparison is within 4 standard errors, and every standard error is bounded from above by
// what the sample size allows (se_bound, ngp_se_bound), so that a huge error bar cannot make a
// comparison pass; loops over lags count the lags they compared, so that a loop over no lags fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <initializer_list>
#include <string>

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

  /// The analysis after every replica of `paths` (species `species`, -1 for all) within `window`.
  static MsdAnalysis accumulated(const std::vector<std::string>& paths, const MsdSettings& s, const FrameWindow& window = {},
                                 int species = -1) {
    MsdAnalysis a(s, paths.size(), "msd.json");
    TrajectoryNeeds needs;
    needs.positions = true;
    needs.orientations = true;
    needs.window = window;
    for_each_replica(paths, needs, [&](const Trajectory& t, std::size_t) { a.accumulate(t, species); });
    return a;
  }
  static MsdResult run(const std::vector<std::string>& paths, const MsdSettings& s, const FrameWindow& window = {}, int species = -1) {
    return accumulated(paths, s, window, species).compute();
  }

  /// One file of Gaussian walks per replica, seeds seed, seed + 1, …
  std::vector<std::string> walk_files(const std::string& stem, std::size_t replicas, std::size_t particles,
                                      const std::vector<double>& time, const Vec3& D, unsigned seed, const Vec3& box = Vec3(20, 20, 20)) {
    std::vector<std::string> paths;
    for (unsigned r = 0; r < replicas; ++r) {
      paths.push_back(file(stem + std::to_string(r) + ".h5"));
      gaussian_walks(particles, time, D, seed + r, box).write(paths.back());
    }
    return paths;
  }
};

/// Mean and variance of a squared displacement Q and of Q² (the moments behind the MSD and the NGP).
struct SquaredDisplacementMoments {
  double m2 = 0, var2 = 0, m4 = 0, var4 = 0;  // E Q, Var Q, E Q², Var Q²
};

/// Q = Σ_a σ_a² z_a² for a Gaussian displacement with per-axis variances σ_a² (z_a standard normal),
/// from its cumulants κ_n = 2^{n−1} (n − 1)! Σ_a σ_a^{2n}.
SquaredDisplacementMoments gaussian_moments(std::initializer_list<double> variances) {
  double k[5] = {0, 0, 0, 0, 0};
  for (double s : variances) {
    k[1] += s;
    k[2] += 2 * s * s;
    k[3] += 8 * s * s * s;
    k[4] += 48 * s * s * s * s;
  }
  const double mu2 = k[2] + k[1] * k[1];
  const double mu4 = k[4] + 4 * k[3] * k[1] + 3 * k[2] * k[2] + 6 * k[2] * k[1] * k[1] + std::pow(k[1], 4);
  return {k[1], k[2], mu2, mu4 - mu2 * mu2};
}

/// Upper bound on the standard error of a mean over `particles` independent particles (every time
/// origin) and `samples` error samples (replicas or origin blocks) of a per-particle quantity of
/// variance `var`. Averaging one particle over correlated time origins cannot raise the variance
/// above that of a single origin, so a sample's variance is at most var/particles and the standard
/// error at most √(var/(particles · samples)); the factor 2 covers the scatter of the estimated
/// standard error itself (χ² with samples − 1 degrees of freedom).
double se_bound(double var, std::size_t particles, std::size_t samples) {
  return 2.0 * std::sqrt(var / static_cast<double>(particles * samples));
}

/// The NGP α = m4/(c m2²) − 1 with a fixed constant c, to first order δα = (1 + α)(δm4/m4 − 2 δm2/m2):
/// each term bounded as in se_bound.
double ngp_se_bound(const SquaredDisplacementMoments& m, double alpha, std::size_t particles, std::size_t samples) {
  return (1 + alpha) * (se_bound(m.var4, particles, samples) / m.m4 + 2 * se_bound(m.var2, particles, samples) / m.m2);
}

/// Checks standard errors against their bounds and remembers the largest ratio, printed at the end
/// of each test to show how much room the bounds leave.
class ErrorBounds {
 public:
  void check(double se, double bound, const std::string& what) {
    EXPECT_LT(se, bound) << what;
    worst_ = std::max(worst_, se / bound);
  }
  ~ErrorBounds() { std::printf("largest standard error / its bound: %.3f\n", worst_); }

 private:
  double worst_ = 0;
};

/// Bound on the error of the least-squares slope of the MSD over the fit window: the slope is
/// Σ_k c_k y_k with c_k = (t_k − t̄)/Σ(t − t̄)² over the window's lags, so its error is at most
/// Σ|c_k| times the largest bound on an MSD error in the window (`msd_bound(t)`, rising with t).
double slope_se_bound(const MsdResult& r, const std::function<double(double)>& msd_bound) {
  std::vector<double> t;
  for (double l : r.lag)
    if (l >= r.fit_t_min * (1 - 1e-9) && l <= r.fit_t_max * (1 + 1e-9)) t.push_back(l);
  EXPECT_GE(t.size(), 2u);
  double mean = 0, stt = 0, sum_abs = 0;
  for (double l : t) mean += l / static_cast<double>(t.size());
  for (double l : t) stt += (l - mean) * (l - mean);
  for (double l : t) sum_abs += std::abs(l - mean) / stt;
  return sum_abs * msd_bound(t.back());
}

}  // namespace

TEST_F(MsdTest, GaussianWalksGiveLinearMsdPerAxisAndZeroNgp) {
  ErrorBounds bounds;
  const Vec3 D(0.5, 0.5, 2.0);
  const std::size_t particles = 200, replicas = 10;
  const auto paths = walk_files("walk", replicas, particles, linear_times(201, 0.1), D, 100, Vec3(5, 6, 7));
  MsdSettings s;
  s.reference = MsdReference::Vector;
  s.direction = Vec3::UnitZ();
  const MsdResult r = run(paths, s);
  ASSERT_GT(r.lag.size(), 10u);
  EXPECT_TRUE(r.uniform_frames);
  // a few lags across the range (every lag would be many correlated comparisons at 4 σ)
  for (std::size_t c : {std::size_t{0}, r.lag.size() / 4, r.lag.size() / 2, 3 * r.lag.size() / 4}) {
    const double t = r.lag[c], x = 2 * D.x() * t, z = 2 * D.z() * t;  // per-axis variances 2 D_a t
    const auto check = [&](const char* name, const SquaredDisplacementMoments& m) {
      const auto& comp = r.component(name);
      EXPECT_NEAR(comp.msd[c], m.m2, 4 * comp.msd_error[c]) << name << " t=" << t;
      bounds.check(comp.msd_error[c], se_bound(m.var2, particles, replicas), std::string(name) + " t=" + std::to_string(t));
    };
    check("x", gaussian_moments({x}));
    check("z", gaussian_moments({z}));
    check("par", gaussian_moments({z}));
    check("perp", gaussian_moments({x, x}));
    check("tot", gaussian_moments({x, x, z}));
    for (const auto& [name, m] : {std::pair{"x", gaussian_moments({x})}, std::pair{"z", gaussian_moments({z})},
                                  std::pair{"perp", gaussian_moments({x, x})}}) {
      const auto& comp = r.component(name);
      EXPECT_NEAR(comp.ngp[c], 0.0, 4 * comp.ngp_error[c]) << name << " t=" << t;
      bounds.check(comp.ngp_error[c], ngp_se_bound(m, 0.0, particles, replicas), std::string(name) + " t=" + std::to_string(t));
    }
  }
  // the fit: D per component, D_tot = (D_par + 2 D_perp)/3 identically (spec 50 §1.3)
  const auto& par = r.component("par").diffusion;
  const auto& perp = r.component("perp").diffusion;
  const auto& tot = r.component("tot").diffusion;
  EXPECT_NEAR(par.value, D.z(), 4 * par.error);
  EXPECT_NEAR(perp.value, 0.5 * (D.x() + D.y()), 4 * perp.error);
  // D = slope / (2d)
  bounds.check(par.error, slope_se_bound(r, [&](double t) { return se_bound(gaussian_moments({2 * D.z() * t}).var2, particles, replicas); }) / 2,
               "D_par");
  bounds.check(perp.error, slope_se_bound(r, [&](double t) {
                 return se_bound(gaussian_moments({2 * D.x() * t, 2 * D.y() * t}).var2, particles, replicas);
               }) / 4, "D_perp");
  EXPECT_NEAR(tot.value, (par.value + 2 * perp.value) / 3, 1e-12 * tot.value);
  EXPECT_NEAR(r.fit_mean_beta, 1.0, 0.05);
}

TEST_F(MsdTest, AnisotropicNgpConstantMakesTheAnisotropicGaussianZero) {
  ErrorBounds bounds;
  const Vec3 D(0.2, 0.2, 3.0);
  const std::size_t particles = 300, replicas = 3;
  const auto paths = walk_files("aniso", replicas, particles, linear_times(101, 0.05), D, 7);
  MsdSettings s;
  s.reference = MsdReference::Vector;
  s.direction = Vec3::UnitZ();
  s.ngp_constant = "anisotropic";
  const MsdResult aniso = run(paths, s);
  s.ngp_constant = "isotropic";
  const MsdResult iso = run(paths, s);
  // c'_2,3 for D_par/D_perp = 15: the isotropic 5/3 reads a spurious positive α_2
  const auto c_aniso = [](double dp, double dq) {
    return (3 * dp * dp + 8 * dq * dq + 4 * dp * dq) / (dp * dp + 4 * dq * dq + 4 * dp * dq);
  };
  const double c_exact = c_aniso(3.0, 0.2);
  std::size_t compared = 0;
  for (std::size_t c = 0; c < aniso.lag.size(); ++c) {
    const double t = aniso.lag[c], dp = 2 * D.z() * t, dq = 2 * D.x() * t;  // per-component variances
    const SquaredDisplacementMoments tot = gaussian_moments({dq, dq, dp});
    // c' is estimated from the par and perp second moments: δ ln c' adds to the bound of the
    // isotropic NGP through its derivatives (central differences of c' written out above)
    const double h = 1e-6, lnc_dp = (std::log(c_aniso(dp * (1 + h), dq)) - std::log(c_aniso(dp * (1 - h), dq))) / (2 * h * dp),
                 lnc_dq = (std::log(c_aniso(dp, dq * (1 + h))) - std::log(c_aniso(dp, dq * (1 - h)))) / (2 * h * dq);
    const double bound = ngp_se_bound(tot, 0.0, particles, replicas) +
                         std::abs(lnc_dp) * se_bound(gaussian_moments({dp}).var2, particles, replicas) +
                         std::abs(lnc_dq) * se_bound(gaussian_moments({dq, dq}).var2 / 4, particles, replicas);
    const auto& a = aniso.component("tot");
    EXPECT_NEAR(a.ngp[c], 0.0, 4 * a.ngp_error[c]) << "t=" << t;
    bounds.check(a.ngp_error[c], bound, std::string("t=") + std::to_string(t));
    const auto& i = iso.component("tot");
    const double alpha_iso = c_exact / (5.0 / 3.0) - 1.0;
    EXPECT_NEAR(i.ngp[c], alpha_iso, 4 * i.ngp_error[c]) << "t=" << t;
    bounds.check(i.ngp_error[c], ngp_se_bound(tot, alpha_iso, particles, replicas), std::string("t=") + std::to_string(t));
    ++compared;
  }
  // 101 uniform frames at 10 lags per decade: the whole frame lags 1, 2, 3, 4, 5, 6, 8, 10, 13, 16,
  // 20, 25, 32, 40, 50, 63, 79, 100 (round(10^(k/10)) without repeats)
  EXPECT_GE(compared, 18u);
}

namespace {

/// Exact moments of x = a Σ_{k steps} s with P(s = ±1) = p/2, P(s = 0) = 1 − p: the lattice
/// distribution of the sum by repeated convolution, then E x², Var x², E x⁴, Var x⁴.
SquaredDisplacementMoments jump_moments(int steps, double p, double a) {
  std::vector<double> prob{1.0};  // prob[j] = P(sum = j − offset), offset = current step count
  for (int k = 0; k < steps; ++k) {
    std::vector<double> next(prob.size() + 2, 0.0);
    for (std::size_t j = 0; j < prob.size(); ++j) {
      next[j] += 0.5 * p * prob[j];
      next[j + 1] += (1 - p) * prob[j];
      next[j + 2] += 0.5 * p * prob[j];
    }
    prob.swap(next);
  }
  double e2 = 0, e4 = 0, e8 = 0;
  for (std::size_t j = 0; j < prob.size(); ++j) {
    const double x = a * (static_cast<double>(j) - steps), x2 = x * x;
    e2 += prob[j] * x2;
    e4 += prob[j] * x2 * x2;
    e8 += prob[j] * x2 * x2 * x2 * x2;
  }
  return {e2, e4 - e2 * e2, e4, e8 - e4 * e4};
}

}  // namespace

TEST_F(MsdTest, NonGaussianJumpsMatchTheClosedFormNgp) {
  ErrorBounds bounds;
  // Each frame interval every particle jumps by ±a along x with probability p, else stays:
  // after k intervals the jump count is Binomial(k, p) and
  //   <x²> = k p a²,  <x⁴> = a⁴ (k p (1 − p)(1 − 6p(1 − p))... ) — use the exact moments of a sum of
  // k iid steps s with <s²> = p a², <s⁴> = p a⁴:  <x⁴> = k <s⁴> + 3 k (k − 1) <s²>²,
  // so α_2,1 = <x⁴>/(3<x²>²) − 1 = (1/p − 3)/(3k).
  const double p = 0.1, a = 0.5;
  const std::size_t particles = 500, replicas = 4;
  std::vector<std::string> paths;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  for (unsigned r = 0; r < replicas; ++r) {
    auto t = gaussian_walks(particles, linear_times(41, 1.0), Vec3(0, 0, 0), 1);
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
  std::size_t compared = 0;
  for (std::size_t c = 0; c < r.lag.size(); ++c) {
    const double k = r.lag[c], alpha = (1.0 / p - 3.0) / (3.0 * k);
    const SquaredDisplacementMoments m = jump_moments(static_cast<int>(std::lround(k)), p, a);
    EXPECT_NEAR(x.msd[c], k * p * a * a, 4 * x.msd_error[c]);
    bounds.check(x.msd_error[c], se_bound(m.var2, particles, replicas), std::string("k=") + std::to_string(k));
    EXPECT_NEAR(x.ngp[c], alpha, 4 * x.ngp_error[c]) << "k=" << k;
    bounds.check(x.ngp_error[c], ngp_se_bound(m, alpha, particles, replicas), std::string("k=") + std::to_string(k));
    ++compared;
  }
  EXPECT_GE(compared, 40u);  // every lag of 41 frames
}

TEST_F(MsdTest, SingleReplicaUsesOriginBlocksForErrorsAndLogFramesAreBinned) {
  ErrorBounds bounds;
  // log-spaced frames: t_k = 0.01·10^(k/10); the lag classes are log bins
  std::vector<double> time{0.0};
  for (int k = 0; k <= 40; ++k) time.push_back(0.01 * std::pow(10.0, k / 10.0));
  const std::string path = file("log.h5");
  const std::size_t particles = 400, blocks = 10;
  gaussian_walks(particles, time, Vec3(1, 1, 1), 11).write(path);
  MsdSettings s;
  const MsdResult r = run({path}, s);
  EXPECT_FALSE(r.uniform_frames);
  EXPECT_EQ(r.samples, blocks);
  std::size_t compared = 0;
  for (std::size_t c = 0; c < r.lag.size(); ++c) {
    const auto& tot = r.component("tot");
    if (std::isnan(tot.msd_error[c])) continue;  // origins in one block only
    // A log bin holds lags t_lo ≤ t < 10^0.1 t_lo, and a block of origins may hold only some of
    // them: besides the sampling noise (se_bound at the bin's largest lag, ≤ 10^0.1 × the mean lag),
    // the block means spread over 6 D (t_hi − t_lo) ≤ 6 (10^0.1 − 1) lag, whose standard deviation is
    // at most half that (Popoviciu); the two add (Minkowski) before the division by √blocks.
    const double v = 2 * 1.0 * r.lag[c] * std::pow(10.0, 0.1), spread = 3 * (std::pow(10.0, 0.1) - 1) * r.lag[c];
    const double bound = se_bound(gaussian_moments({v, v, v}).var2, particles, blocks) + 2 * spread / std::sqrt(static_cast<double>(blocks));
    EXPECT_NEAR(tot.msd[c], 6 * r.lag[c], 5 * tot.msd_error[c] + 1e-9 * r.lag[c]) << r.lag[c];
    bounds.check(tot.msd_error[c], bound, std::to_string(r.lag[c]));
    ++compared;
  }
  // 47 bins of lag, tenths of a decade from 0.0026 (t_2 − t_1) to 100; the 5 bins below 0.0079 hold
  // pairs of origins in one block only (frames 0 … 4, or 5 alone), which have no error
  EXPECT_GE(compared, 42u);
}

TEST_F(MsdTest, SamplesOfAComponentAreTheCurvesBehindItsMsdAndError) {
  const auto paths = walk_files("samples", 3, 50, linear_times(31, 0.1), Vec3(1, 2, 3), 40);
  MsdSettings s;
  s.reference = MsdReference::Vector;
  const MsdAnalysis a = accumulated(paths, s);
  const MsdResult r = a.compute();
  for (const char* name : {"tot", "x", "par", "perp"}) {
    const CurveSamples c = a.samples_of(name);
    EXPECT_EQ(c.count(), 3u) << name;
    EXPECT_EQ(c.mean(), r.component(name).msd) << name;
    EXPECT_EQ(c.standard_error(), r.component(name).msd_error) << name;
  }
  EXPECT_THROW(a.samples_of("body_x"), RuntimeFailure);
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
  tool::ConfigNode cfg(j, "msd.json");
  EXPECT_EQ(input_error([&] { parse_msd_settings(cfg); }).json_path(), "director_species");
}

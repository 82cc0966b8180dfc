// Van Hove stage on Gaussian random walks: G_s equals the Gaussian reference (the exact answer for
// a Gaussian process) in every component's well-populated bins, and the normalisation
// ∫ v_d G dr = 1 holds.
#include <gtest/gtest.h>

#include "anisodyn/analysis/van_hove.hpp"
#include "scratch_dir.hpp"
#include "synthetic_trajectory.hpp"
#include "time_window.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

class VanHoveTest : public anisodyn::testing_support::ScratchDirTest {
 protected:
  VanHoveTest() : ScratchDirTest("vanhove") {}
};

// Components whose displacement is an isotropic Gaussian in its d dimensions: x, z and perp
// (D_x = D_y) of an anisotropic walk, and the total displacement of an isotropic one (the total of
// an anisotropic walk is not isotropic: that is what the ellipsoidal reference is for).
void check_gaussian(const std::vector<std::string>& paths, const std::vector<std::string>& components, const Vec3& Dv) {
  VanHoveSettings s;
  s.times = {0.5, 2.0};
  s.components = components;
  s.bins = 200;
  s.bin_width = std::nullopt;
  VanHoveAnalysis a(s, paths.size());
  TrajectoryNeeds needs;
  needs.positions = true;
  for_each_replica(paths, needs, [&](const Trajectory& t, std::size_t) { a.accumulate(t, -1); });
  const auto curves = a.compute();
  ASSERT_EQ(curves.size(), 2 * components.size());
  for (const auto& c : curves) {
    // the exact second moment of each component: 2 d D t
    const double D = c.component == "z" ? Dv.z() : c.component == "tot" ? Dv.mean() : Dv.x();
    EXPECT_NEAR(c.mean_square, 2 * c.dimension * D * c.time, 0.03 * c.mean_square) << c.component;
    double norm = 0;
    std::size_t checked = 0;
    for (std::size_t j = 0; j < c.r.size(); ++j) {
      const double w = c.r[1] - c.r[0], r0 = c.r[j] - 0.5 * w;
      const double measure = c.dimension == 1 ? 2 * w : c.dimension == 2 ? M_PI * ((r0 + w) * (r0 + w) - r0 * r0)
                                                                           : 4 * M_PI / 3 * (std::pow(r0 + w, 3) - std::pow(r0, 3));
      norm += c.g[j] * measure;
      // bins holding ≥ 1% of the probability: G within 4 standard errors of the Gaussian
      if (c.gaussian[j] * measure > 0.01 && j % 10 == 0) {
        EXPECT_NEAR(c.g[j], c.gaussian[j], 4 * c.g_error[j]) << c.component << " t=" << c.time << " r=" << c.r[j];
        ++checked;
      }
    }
    EXPECT_NEAR(norm + c.overflow, 1.0, 1e-9) << c.component;
    EXPECT_GT(checked, 3u);
  }
}

TEST_F(VanHoveTest, GaussianWalksHaveGaussianVanHoveFunctions) {
  for (const Vec3& D : {Vec3(1.0, 1.0, 0.25), Vec3(0.5, 0.5, 0.5)}) {
    std::vector<std::string> paths;
    for (unsigned r = 0; r < 8; ++r) {
      paths.push_back(file("walk" + std::to_string(r) + ".h5"));
      anisodyn::testing_support::gaussian_walks(400, anisodyn::testing_support::linear_times(51, 0.1), D, 90 + r).write(paths.back());
    }
    if (D.z() == D.x()) check_gaussian(paths, {"tot"}, D);
    else check_gaussian(paths, {"x", "z", "perp"}, D);
  }
}

TEST_F(VanHoveTest, AWindowGivesTheVanHoveFunctionOfTheTruncatedTrajectory) {
  std::vector<std::string> full, cut;
  for (unsigned r = 0; r < 2; ++r) {
    const auto walk = anisodyn::testing_support::gaussian_walks(100, anisodyn::testing_support::linear_times(81, 0.1), Vec3(1, 1, 1), 30 + r);
    full.push_back(file("full" + std::to_string(r) + ".h5"));
    cut.push_back(file("cut" + std::to_string(r) + ".h5"));
    walk.write(full.back());
    anisodyn::testing_support::frames_of(walk, 40, 41).write(cut.back());  // t = 4 … 8
  }
  auto analyse = [](const std::vector<std::string>& paths, const FrameWindow& w) {
    VanHoveSettings s;
    s.times = {0.5, 3.0};
    s.components = {"tot", "z"};
    VanHoveAnalysis a(s, paths.size());
    TrajectoryNeeds needs;
    needs.positions = true;
    needs.window = w;
    for_each_replica(paths, needs, [&](const Trajectory& t, std::size_t) { a.accumulate(t, -1); });
    return a.compute();
  };
  const auto windowed = analyse(full, anisodyn::testing_support::time_window(4.0, 8.0)), truncated = analyse(cut, {});
  ASSERT_EQ(windowed.size(), truncated.size());
  for (std::size_t k = 0; k < windowed.size(); ++k) {
    EXPECT_EQ(windowed[k].time, truncated[k].time);
    EXPECT_EQ(windowed[k].g, truncated[k].g);
    EXPECT_EQ(windowed[k].mean_square, truncated[k].mean_square);
  }
}

}  // namespace

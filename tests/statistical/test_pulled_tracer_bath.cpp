// The pulled tracer through the whole production path (DmcRunner: preliminary balance with the
// tracer as the reference species and A_0 = overlap pass by default, the bath as the clock; then
// the active microrheology stage), against what a bath must do to it:
//  - an ideal bath of points, which relax a thousand times faster than the tracer, leaves the
//    friction at its free value: γ_eff/γ_0 = 1 within 3 SE;
//  - the overlap pass A_0 of that bath differs from 1 and equals its value from the geometry of
//    the displaced exclusion sphere (an independent quadrature, tests/support); and so does the
//    A_0 ≈ 0.9 of a ten times denser bath at Pe = 0, where the equilibrium of the whole chain makes
//    the bath at every tracer trial exactly uniform outside the tracer;
//  - a hard-sphere bath at η = 0.30 (equal spheres, Pe = 2) raises the friction: γ_eff/γ_0 − 1 > 4 SE.
// Fixed seeds; every asserted SE is also bounded from above.
#include <gtest/gtest.h>

#include <cstdio>

#include "anisodyn/analysis/replica_statistics.hpp"
#include "pulled_tracer_campaign.hpp"
#include "scratch_dir.hpp"

using namespace anisodyn;
using namespace anisodyn::testing_support;

namespace {

class PulledTracerBath : public ScratchDirTest {
 protected:
  PulledTracerBath() : ScratchDirTest("tracer-bath") {}

  struct Campaign {
    std::vector<std::string> paths;
    std::vector<nlohmann::json> summaries;
  };
  Campaign run(const BathSystem& bath, const TracerRun& r, int replicas, const std::string& name) {
    Campaign c;
    for (int k = 0; k < replicas; ++k) {
      const State start = tracer_in_bath(bath, 500 + static_cast<std::uint64_t>(k));
      c.paths.push_back(file(name + std::to_string(k) + ".h5"));
      c.summaries.push_back(run_tracer_replica(start, r, static_cast<std::uint64_t>(k), c.paths.back()));
    }
    return c;
  }
};

/// The friction of the campaign's replicas, printed under `label`.
auto friction_of(const std::vector<std::string>& paths, double pe, double tracer_diameter, const char* label) {
  const auto result = analyse_tracer(paths, pe, tracer_diameter);
  std::printf("%s: gamma_eff/gamma_0 = %.4f ± %.4f (jackknife), <v> = %.4f ± %.4f, per-replica sd %.4f\n", label,
              result.gamma_ratio.value, result.gamma_ratio.error, result.velocity.value, result.velocity.error, result.velocity_scatter);
  return result;
}

analysis::Estimate tracer_summary_mean(const std::vector<nlohmann::json>& summaries, const char* key) {
  std::vector<double> v;
  for (const auto& s : summaries) v.push_back(s.at("tracer").at(key).get<double>());
  return analysis::mean_and_error(v);
}

TEST_F(PulledTracerBath, IdealPointBathLeavesTheFrictionFreeAndPassesAsItsGeometrySays) {
  BathSystem bath;
  bath.box = 3.0;
  bath.points = 26;
  bath.bath_diameter = 0.001;  // D_bath = 1000 D_tracer: the bath relaxes at once around the tracer
  TracerRun r;
  r.pe = 1.0;
  r.tracer_dt = 0.01;
  r.cycles = 60000;
  const Campaign c = run(bath, r, 24, "points");
  const auto result = friction_of(c.paths, r.pe, bath.tracer_diameter, "ideal point bath");
  EXPECT_LT(result.gamma_ratio.error, 0.05);
  EXPECT_NEAR(result.gamma_ratio.value, 1.0, 3.0 * result.gamma_ratio.error);

  // A_0 from geometry: the proposal box of the run, the 26 points uniform outside the tracer.
  const double R = bath.contact(), beta_force = r.pe / (0.5 * bath.tracer_diameter);
  const double d_par = c.summaries.front().at("tracer").at("parallel_step").get<double>();
  const double d_perp = std::sqrt(2.0 * stokes_einstein(bath.tracer_diameter) * r.tracer_dt);
  const double free_volume = std::pow(bath.box, 3) - 4.0 / 3.0 * std::numbers::pi * R * R * R;
  const PointBathTrial theory = point_bath_trial(bath.points, free_volume, R, beta_force, d_par, d_perp);
  const analysis::Estimate a0 = tracer_summary_mean(c.summaries, "overlap_pass");
  const analysis::Estimate at = tracer_summary_mean(c.summaries, "acceptance");
  std::printf("A_0 = %.5f ± %.5f (geometry %.5f); A_t = %.5f ± %.5f (geometry %.5f)\n", a0.value, a0.error, theory.a0, at.value, at.error,
              theory.at);
  EXPECT_LT(1.0 - theory.a0, 0.05);
  EXPECT_GT(1.0 - theory.a0, 0.02);  // the system tests A_0 where it is not 1
  EXPECT_LT(a0.error, 0.1 * (1.0 - theory.a0));
  EXPECT_NEAR(a0.value, theory.a0, 4.0 * a0.error);
  EXPECT_NEAR(at.value, theory.at, 4.0 * at.error);
  // The single-trial theory's own prediction of the mapped friction, for the record.
  const double E = 1.5 * theory.at - 0.5 * theory.a0;
  std::printf("single-trial theory with A_0 = overlap pass: gamma_eff/gamma_0 = %.4f\n",
              stokes_einstein(bath.tracer_diameter) * beta_force * E * r.tracer_dt / 3.0 / theory.drift);
}

TEST_F(PulledTracerBath, DensePointBathAtZeroForcePassesAsItsGeometrySays) {
  // At Pe = 0 DMC samples the equilibrium of tracer and bath together and picks the particle of a
  // trial independently of the state, so every tracer trial sees the 80 points independent and
  // uniform outside it: A_0 is the geometric expectation exactly. (With a force, the points the
  // tracer has just uncovered behind it stay away until they are next tried, about one cycle: a
  // memory that a single-trial calculation leaves out.)
  BathSystem bath;
  bath.box = 2.0;  // the minimum image needs twice the tracer's self cut-off
  bath.points = 80;
  bath.bath_diameter = 0.001;
  bath.mc_cycles = 200;
  TracerRun r;
  r.pe = 0.0;
  r.tracer_dt = 0.005;
  r.preliminary_cycles = 2000;
  r.cycles = 12000;
  const Campaign c = run(bath, r, 16, "dense");
  const double R = bath.contact(), d = std::sqrt(2.0 * stokes_einstein(bath.tracer_diameter) * r.tracer_dt);
  const double free_volume = std::pow(bath.box, 3) - 4.0 / 3.0 * std::numbers::pi * R * R * R;
  const PointBathTrial theory = point_bath_trial(bath.points, free_volume, R, 0.0, d, d);
  const analysis::Estimate a0 = tracer_summary_mean(c.summaries, "overlap_pass");
  std::printf("dense point bath, Pe = 0: A_0 = %.5f ± %.5f (geometry %.5f)\n", a0.value, a0.error, theory.a0);
  EXPECT_GT(1.0 - theory.a0, 0.08);
  EXPECT_LT(a0.error, 0.05 * (1.0 - theory.a0));
  EXPECT_NEAR(a0.value, theory.a0, 4.0 * a0.error);
}

TEST_F(PulledTracerBath, HardSphereBathAtPackingFractionPointThreeRaisesTheFriction) {
  BathSystem bath;
  bath.lattice = 4;  // 63 bath spheres + the tracer, all of diameter 1
  bath.box = std::cbrt(64 * std::numbers::pi / 6.0 / 0.30);
  TracerRun r;  // βF δx_∥ = 0.13: the drift per cycle stands out of the noise twice as well as at Pe = 1
  r.pe = 2.0;
  r.tracer_dt = 0.005;
  r.cycles = 50000;
  const Campaign c = run(bath, r, 16, "hs");
  const auto result = friction_of(c.paths, r.pe, bath.tracer_diameter, "hard-sphere bath eta = 0.30");
  EXPECT_LT(result.gamma_ratio.error, 0.2);
  EXPECT_GT(result.gamma_ratio.value - 1.0, 4.0 * result.gamma_ratio.error);
}

}  // namespace

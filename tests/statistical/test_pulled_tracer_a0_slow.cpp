// The tracer's time mapping with both A_0 treatments of spec 10 §4.5 against an independent
// single-trial calculation, in a dense ideal bath of points where A_0 ≈ 0.9 (so that the two
// treatments differ by several percent). The bath relaxes a thousand times faster than the tracer,
// so at every tracer trial it is in equilibrium: 80 points uniform outside the tracer. One trial's
// expected pass, acceptance and drift then follow from the geometry of the displaced exclusion
// sphere (tests/support/pulled_tracer_campaign.hpp), and the mapped velocity of the DMC run must be
// drift / (E δt/3) with E = (3/2)A_t − (1/2)A_0 for the default, E = (3/2)A_t − 1/2 for A_0 ≡ 1.
// Each variant's γ_eff/γ_0 must match its prediction within 3 SE, and the two predictions are more
// than 4 SE apart, so the test tells the treatments apart. Slow: about two CPU-minutes.
#include <gtest/gtest.h>

#include <cstdio>

#include "pulled_tracer_campaign.hpp"
#include "scratch_dir.hpp"

using namespace anisodyn;
using namespace anisodyn::testing_support;

namespace {

class PulledTracerA0 : public ScratchDirTest {
 protected:
  PulledTracerA0() : ScratchDirTest("tracer-a0") {}
};

TEST_F(PulledTracerA0, BothTreatmentsMatchTheSingleTrialTheoryInADensePointBath) {
  BathSystem bath;
  bath.box = 2.0;  // the minimum image needs twice the tracer's self cut-off
  bath.points = 80;
  bath.bath_diameter = 0.001;
  bath.mc_cycles = 500;
  TracerRun r;
  r.pe = 5.0;
  r.tracer_dt = 1e-3;  // spec 10 §4.5's step for Pe = 5: βF δx_∥ = 0.146
  r.cycles = 120000;
  const int replicas = 24;
  const double R = bath.contact(), beta_force = r.pe / (0.5 * bath.tracer_diameter), D = stokes_einstein(bath.tracer_diameter);
  const double d_perp = std::sqrt(2.0 * D * r.tracer_dt), d_par = std::sqrt(d_perp * d_perp + std::pow(D * beta_force * r.tracer_dt, 2));
  const double free_volume = std::pow(bath.box, 3) - 4.0 / 3.0 * std::numbers::pi * R * R * R;
  const PointBathTrial trial = point_bath_trial(bath.points, free_volume, R, beta_force, d_par, d_perp);
  ASSERT_LT(trial.a0, 0.93);  // a bath that really rejects
  std::vector<double> predicted, measured, error;
  for (const std::string a0 : {"overlap_pass", "one"}) {
    r.a0 = a0;
    const double E = 1.5 * trial.at - 0.5 * (a0 == "one" ? 1.0 : trial.a0);
    predicted.push_back(D * beta_force * (E * r.tracer_dt / 3.0) / trial.drift);
    std::vector<std::string> paths;
    for (int k = 0; k < replicas; ++k) {
      paths.push_back(file(a0 + std::to_string(k) + ".h5"));
      run_tracer_replica(tracer_in_bath(bath, 900 + static_cast<std::uint64_t>(k)), r, static_cast<std::uint64_t>(k), paths.back());
    }
    const auto result = analyse_tracer(paths, r.pe, bath.tracer_diameter);
    measured.push_back(result.gamma_ratio.value);
    error.push_back(result.gamma_ratio.error);
    std::printf("A_0 = %-12s gamma_eff/gamma_0 = %.4f ± %.4f, single-trial theory %.4f (A_0 %.4f, A_t %.4f)\n", a0.c_str(),
                result.gamma_ratio.value, result.gamma_ratio.error, predicted.back(), trial.a0, trial.at);
    EXPECT_LT(result.gamma_ratio.error, 0.02);
    EXPECT_NEAR(result.gamma_ratio.value, predicted.back(), 3.0 * result.gamma_ratio.error);
  }
  EXPECT_GT(std::abs(predicted[0] - predicted[1]), 4.0 * std::max(error[0], error[1]));
}

}  // namespace

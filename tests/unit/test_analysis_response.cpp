// Response times (spec 50 §8) on signals with closed-form answers: an exponential step response
// B(t) = B_on − (B_on − B_eq) e^{−t/τ} after switch-on and B_eq + (B_on − B_eq) e^{−t/τ_off} after
// switch-off (t_ON = τ ln((B_on − B_eq)/(0.05 B_on)), t_OFF = τ_off ln((B_on − B_eq)/(0.05 B_eq)),
// t_OFF,95 = τ_off ln 20) plus small noise; the modified Z-score on exact numbers and on a planted
// outlier replica; the switch cycles of a field_switches observable; the stage on orientations
// whose B_2 is an exact mixture (B_2 = |2p − 1|); and bad inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "anisodyn/analysis/response_times.hpp"
#include "anisodyn/core/error.hpp"
#include "input_error.hpp"
#include "scratch_dir.hpp"
#include "synthetic_trajectory.hpp"
#include "time_window.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;
using anisodyn::testing_support::input_error;

namespace {

struct Step {
  double b_eq = 0.0, b_on = 0.8, tau = 1.0, tau_off = 1.5;
  double t_on = 10.0, t_off = 30.0, t_end = 50.0, dt = 0.02, noise = 0.005;
};

/// The step-response signal of `Step` at the frame times, with Gaussian noise.
void step_signal(const Step& s, unsigned seed, std::vector<double>& time, std::vector<double>& b) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, s.noise);
  time.clear();
  b.clear();
  const auto frames = static_cast<std::size_t>(std::llround(s.t_end / s.dt));
  for (std::size_t k = 0; k <= frames; ++k) {
    const double t = static_cast<double>(k) * s.dt;
    double v = s.b_eq;
    if (t >= s.t_off) v = s.b_eq + (s.b_on - s.b_eq) * std::exp(-(t - s.t_off) / s.tau_off);
    else if (t >= s.t_on) v = s.b_on - (s.b_on - s.b_eq) * std::exp(-(t - s.t_on) / s.tau);
    time.push_back(t);
    b.push_back(v + g(rng));
  }
}

SwitchCycle cycle_of(const Step& s) {
  SwitchCycle c;
  c.on = s.t_on;
  c.off = s.t_off;
  return c;
}

/// Resolution of a threshold time: the smoothing window plus one frame.
double resolution(std::size_t window, double dt) { return static_cast<double>(window + 1) * dt; }

Quat about_z(double phi) { return Quat(Eigen::AngleAxisd(phi, Vec3::UnitZ())); }

/// Orientations with B_2,L = |2p − 1| exactly: L along z, a fraction p with W along x, the rest
/// rotated by 90° about z (spec 50 §3.2; see test_analysis_order).
std::vector<Quat> biaxial_mixture(std::size_t n, double b2) {
  const auto m = static_cast<std::size_t>(std::llround(static_cast<double>(n) * (1.0 + b2) / 2.0));
  std::vector<Quat> q;
  for (std::size_t i = 0; i < n; ++i) q.push_back(i < m ? Quat::Identity() : about_z(M_PI / 2));
  return q;
}

/// In-memory trajectory whose B_2 follows the noiseless step of `s`, with a field_switches observable.
Trajectory step_trajectory(const Step& s, std::size_t n, bool with_observable, double time_scale = 1.0) {
  std::vector<double> time, b;
  Step quiet = s;
  quiet.noise = 0;
  step_signal(quiet, 1, time, b);
  Trajectory t;
  t.path = "memory";
  t.frames = time.size();
  t.particles = n;
  for (std::size_t f = 0; f < t.frames; ++f) {
    t.time.push_back(time[f] * time_scale);
    t.step.push_back(static_cast<std::int64_t>(f));
    t.box.insert(t.box.end(), {10, 10, 10});
    for (const Quat& q : biaxial_mixture(n, b[f])) t.orientation.insert(t.orientation.end(), {q.w(), q.x(), q.y(), q.z()});
  }
  t.species.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) t.id.push_back(static_cast<std::int64_t>(i));
  t.species_table = {Species{"H", Shape::cuboid(1, 2, 8), 1.0, Vec3::Ones(), Vec3::Ones()}};
  if (with_observable)
    t.observables["field_switches"] = ObservableSeries{{0.0, s.t_on * time_scale, s.t_off * time_scale},
                                                       {0, 0, 0, 1, 1, 1, 0, 0, 0, 1, 0, 0}, 4};
  return t;
}

}  // namespace

TEST(ResponseTimes, MovingAverageIsCentredAndTruncated) {
  const std::vector<double> x{0, 1, 2, 3, 4, 10};
  const auto y = moving_average(x, 3);
  EXPECT_DOUBLE_EQ(y[0], 0.5);
  EXPECT_DOUBLE_EQ(y[2], 2.0);
  EXPECT_DOUBLE_EQ(y[5], 7.0);
  EXPECT_EQ(moving_average(x, 1), x);
  EXPECT_DOUBLE_EQ(moving_average(x, 2)[2], 2.0);  // an even window is widened to 3
}

TEST(ResponseTimes, StepResponseGivesTauLn20) {
  Step s;  // B_eq = 0: B = B_on (1 − e^{−t/τ}) → t_ON = τ ln 20
  std::vector<double> time, b;
  step_signal(s, 42, time, b);
  const ReplicaResponse r = response_times(time, b, cycle_of(s));
  EXPECT_EQ(r.window_on, 11u);  // 1% of the 1000 on-frames, made odd
  EXPECT_NEAR(r.b_on, s.b_on, 4 * s.noise / std::sqrt(250.0));
  EXPECT_NEAR(r.t_on, s.tau * std::log(20.0), resolution(r.window_on, s.dt));
  EXPECT_NEAR(r.t_off95, s.tau_off * std::log(20.0), resolution(r.window_off, s.dt));
  std::printf("t_ON = %.4f (tau ln 20 = %.4f, resolution %.3f); t_OFF95 = %.4f (%.4f)\n", r.t_on, std::log(20.0),
              resolution(r.window_on, s.dt), r.t_off95, s.tau_off * std::log(20.0));
}

TEST(ResponseTimes, NonZeroOffStateGivesAllThreeTimes) {
  Step s;
  s.b_eq = 0.1;
  s.noise = 0.0005;  // the literal t_OFF crosses where the slope is only 0.05 B_eq/τ_off (ill-conditioned, §8.1)
  std::vector<double> time, b;
  step_signal(s, 7, time, b);
  const ReplicaResponse r = response_times(time, b, cycle_of(s));
  EXPECT_NEAR(r.b_eq_off, s.b_eq, 4 * s.noise / std::sqrt(500.0));
  EXPECT_NEAR(r.t_on, s.tau * std::log((s.b_on - s.b_eq) / (0.05 * s.b_on)), resolution(r.window_on, s.dt));
  EXPECT_NEAR(r.t_off, s.tau_off * std::log((s.b_on - s.b_eq) / (0.05 * s.b_eq)), resolution(r.window_off, s.dt));
  EXPECT_NEAR(r.t_off95, s.tau_off * std::log(20.0), resolution(r.window_off, s.dt));
  EXPECT_EQ(r.reference_frames, 500u);
  EXPECT_EQ(r.on_frames, 1000u);
  EXPECT_EQ(r.off_frames, 1001u);
}

TEST(ResponseTimes, ModifiedZScoreOnExactNumbers) {
  // median 3, MAD 1: M(100) = 0.6745·97 → rejected and flagged; M(−50) rejected, not one-sided
  const auto o = reject_outliers({1, 2, 3, 4, 100, -50, 3.5}, 3.5);
  EXPECT_NEAR(o.score[4], 0.6745 * 97, 1e-12);
  EXPECT_EQ(o.rejected, (std::vector<char>{0, 0, 0, 0, 1, 1, 0}));
  EXPECT_EQ(o.one_sided, (std::vector<char>{0, 0, 0, 0, 1, 0, 0}));
  EXPECT_EQ(o.rejected_count, 2u);
  EXPECT_EQ(o.one_sided_count, 1u);
  EXPECT_NEAR(o.retained.value, (1 + 2 + 3 + 4 + 3.5) / 5, 1e-12);
  // MAD = 0: the mean-absolute-deviation fallback, M(6) = 1/(1.253314 · 0.2) = 3.99
  const auto z = reject_outliers({5, 5, 5, 5, 6, std::nan("")}, 3.5);
  EXPECT_TRUE(z.mean_absolute_deviation);
  EXPECT_NEAR(z.score[4], 1.0 / (1.253314 * 0.2), 1e-9);
  EXPECT_EQ(z.rejected_count, 1u);
  EXPECT_EQ(z.missing, 1u);
  EXPECT_TRUE(std::isnan(z.score[5]));
  EXPECT_DOUBLE_EQ(z.retained.value, 5.0);
}

TEST(ResponseTimes, PlantedOutlierReplicaIsRejectedAndOthersKept) {
  std::vector<double> t_on;
  std::size_t window = 0;
  Step s;
  for (unsigned k = 0; k < 12; ++k) {
    Step x = s;
    if (k == 5) x.tau = 4.0;  // the planted slow trajectory
    std::vector<double> time, b;
    step_signal(x, 100 + k, time, b);
    const ReplicaResponse r = response_times(time, b, cycle_of(x));
    window = r.window_on;
    t_on.push_back(r.t_on);
  }
  const auto o = reject_outliers(t_on);
  for (std::size_t k = 0; k < t_on.size(); ++k) {
    EXPECT_EQ(o.rejected[k] != 0, k == 5) << "replica " << k << " M = " << o.score[k];
    EXPECT_EQ(o.one_sided[k] != 0, k == 5);
  }
  EXPECT_EQ(o.used, 11u);
  EXPECT_NEAR(o.retained.value, s.tau * std::log(20.0), resolution(window, s.dt));
  EXPECT_GT(o.retained.error, 0.0);
  std::printf("retained t_ON = %.4f +- %.4f over %zu; outlier M = %.1f\n", o.retained.value, o.retained.error, o.used, o.score[5]);
}

TEST(ResponseTimes, SwitchCyclesFromTheObservable) {
  // initial state off; on at 10 (field y), off at 30, on at 50 (field x), off at 60
  const ObservableSeries sw{{0, 10, 30, 50, 60}, {0, 0, 0, 1, 1, 0, 1, 0, 0, 0, 0, 1, 1, 1, 0, 0, 0, 1, 0, 0}, 4};
  const SwitchCycle c0 = switch_cycle_from_observable(sw, 0, "f.h5");
  EXPECT_EQ(c0.on, 10);
  EXPECT_EQ(c0.off, 30);
  EXPECT_EQ(c0.end, 50);
  EXPECT_TRUE(std::isinf(c0.reference_start));
  ASSERT_TRUE(c0.field.has_value());
  EXPECT_NEAR((*c0.field - Vec3::UnitY()).norm(), 0, 1e-15);
  const SwitchCycle c1 = switch_cycle_from_observable(sw, 1, "f.h5");
  EXPECT_EQ(c1.on, 50);
  EXPECT_EQ(c1.off, 60);
  EXPECT_EQ(c1.reference_start, 30);
  EXPECT_TRUE(std::isinf(c1.end));
  const InputError e = input_error([&] { switch_cycle_from_observable(sw, 2, "f.h5"); });
  EXPECT_EQ(e.json_path(), "/observables/field_switches");
}

TEST(ResponseStage, BiaxialOrderFromOrientationsGivesTOn) {
  // Three replicas whose B_2,L is the exact step (no noise) quantised by 2/N; the mapped times of
  // one replica are stretched by 1% (the switch instants follow), so every replica gives the same
  // t_ON in its own time up to that 1%.
  Step s;
  s.dt = 0.05;
  s.t_on = 5;
  s.t_off = 20;
  s.t_end = 30;
  s.b_eq = 0.1;
  const std::size_t n = 500;
  ResponseSettings rs;
  ResponseAnalysis a(rs);
  a.accumulate(step_trajectory(s, n, true), -1);
  a.accumulate(step_trajectory(s, n, true, 1.01), -1);
  a.accumulate(step_trajectory(s, n, true), -1);
  const ResponseResult r = a.compute();
  EXPECT_EQ(r.main_axis, 2);  // L has U = 1 before the switch-on
  ASSERT_EQ(r.replicas.size(), 3u);
  const double expected = s.tau * std::log((s.b_on - s.b_eq) / (0.05 * s.b_on));
  // resolution: smoothing window + one frame, plus the B_2 quantum 2/N over the slope 0.05 B_on/τ
  const double tol = resolution(r.replicas[0].window_on, s.dt) * 1.01 + (2.0 / n) / (0.05 * s.b_on / s.tau) + 0.01 * expected;
  for (const auto& x : r.replicas) EXPECT_NEAR(x.t_on, expected, tol);
  EXPECT_NEAR(r.replicas[1].switch_on, 1.01 * s.t_on, 1e-12);
  EXPECT_NEAR(r.on.retained.value, expected, tol);
  EXPECT_EQ(r.on.rejected_count, 0u);
  EXPECT_NEAR(r.replicas[0].b_eq_off, s.b_eq, 2.0 / n);
  EXPECT_NEAR(r.replicas[0].t_off95, s.tau_off * std::log(20.0),
              resolution(r.replicas[0].window_off, s.dt) + (2.0 / n) / (0.05 * (s.b_on - s.b_eq) / s.tau_off));
  // the mean curve starts at the switch-on and reaches B_on
  ASSERT_FALSE(r.curve_time.empty());
  EXPECT_NEAR(r.curve.back(), s.b_eq + (s.b_on - s.b_eq) * std::exp(-(s.t_end - s.t_off) / s.tau_off), 2.0 / n);
}

TEST(ResponseStage, ConfigSwitchInstantsAndBadInputs) {
  Step s;
  s.dt = 0.1;
  s.t_on = 5;
  s.t_off = 20;
  s.t_end = 30;
  // no observable and no switch_on: InputError naming the file and the observable path
  ResponseAnalysis a(ResponseSettings{}, "response.json");
  const InputError e = input_error([&] { a.accumulate(step_trajectory(s, 50, false), -1); });
  EXPECT_EQ(e.json_path(), "/observables/field_switches");
  // switch instants from the config
  ResponseSettings rs;
  rs.switch_on = 5.0;
  rs.switch_off = 20.0;
  ResponseAnalysis b(rs, "response.json");
  b.accumulate(step_trajectory(s, 50, false), -1);
  EXPECT_EQ(b.compute().replicas[0].switch_off, 20.0);
  // a switch-on outside the run
  rs.switch_on = 40.0;
  rs.switch_off = 45.0;
  ResponseAnalysis c(rs, "response.json");
  EXPECT_EQ(input_error([&] { c.accumulate(step_trajectory(s, 50, false), -1); }).json_path(), "switch_on");
  // configuration errors
  nlohmann::json j = {{"switch_off", 3.0}};
  tool::ConfigNode cfg(j, "response.json");
  EXPECT_EQ(input_error([&] { parse_response_settings(cfg); }).json_path(), "switch_off");
  nlohmann::json j2 = {{"signal", "Q4"}};
  tool::ConfigNode cfg2(j2, "response.json");
  EXPECT_EQ(input_error([&] { parse_response_settings(cfg2); }).json_path(), "signal");
}

class ResponseFileTest : public anisodyn::testing_support::ScratchDirTest {
 protected:
  ResponseFileTest() : ScratchDirTest("response") {}

  /// 20 boards with identity orientations (S_cube = 1 about x) in `frames` frames 0.5 apart, with
  /// the given field_switches rows (time, state, direction), written to `name`.
  std::string boards_with_switches(const std::string& name, std::size_t frames,
                                   const std::vector<std::pair<double, std::vector<double>>>& switches) {
    anisodyn::testing_support::SyntheticTrajectory st;
    st.time = anisodyn::testing_support::linear_times(frames, 0.5);
    st.position.assign(frames, std::vector<Vec3>(20, Vec3(1, 1, 1)));
    st.orientation.assign(frames, std::vector<Quat>(20, Quat::Identity()));
    st.table = {Species{"H", Shape::cuboid(1, 2, 8), 1.0, Vec3::Ones(), Vec3::Ones()}};
    st.observables.push_back({"field_switches", switches});
    const std::string path = file(name);
    st.write(path);
    return path;
  }
};

TEST_F(ResponseFileTest, FieldSwitchesObservableIsReadFromH5md) {
  const std::string path = boards_with_switches("sw.h5", 40, {{0.0, {0, 1, 0, 0}}, {5.0, {1, 1, 0, 0}}, {12.0, {0, 1, 0, 0}}});
  TrajectoryNeeds needs;
  needs.orientations = true;
  needs.observables = {"field_switches"};
  ResponseSettings rs;
  rs.signal = "S_cube";
  ResponseAnalysis a(rs);
  for_each_replica({path}, needs, [&](const Trajectory& t, std::size_t) { a.accumulate(t, -1); });
  const ResponseResult r = a.compute();
  EXPECT_EQ(r.replicas[0].switch_on, 5.0);
  EXPECT_EQ(r.replicas[0].switch_off, 12.0);
  // identity orientations and the recorded field x: S_cube = 1 throughout
  EXPECT_NEAR(r.replicas[0].b_on, 1.0, 1e-12);
  EXPECT_NEAR(r.curve_time.front(), -5.0, 1e-12);
}

TEST_F(ResponseFileTest, AWindowMeasuresTheSwitchesInsideIt) {
  // two cycles: on at 5, off at 12, on at 20, off at 27; the window from 15 holds the second
  const std::string path = boards_with_switches(
      "two.h5", 80, {{0.0, {0, 1, 0, 0}}, {5.0, {1, 1, 0, 0}}, {12.0, {0, 1, 0, 0}}, {20.0, {1, 1, 0, 0}}, {27.0, {0, 1, 0, 0}}});
  auto analyse = [&](const FrameWindow& w, std::size_t cycle) {
    TrajectoryNeeds needs;
    needs.orientations = true;
    needs.event_observables = {"field_switches"};
    needs.window = w;
    ResponseSettings rs;
    rs.signal = "S_cube";
    rs.cycle = cycle;
    ResponseAnalysis a(rs);
    for_each_replica({path}, needs, [&](const Trajectory& t, std::size_t) { a.accumulate(t, -1); });
    return a.compute();
  };
  const ResponseResult windowed = analyse(anisodyn::testing_support::time_window(15.0, std::nullopt), 0), second = analyse(FrameWindow{}, 1);
  EXPECT_EQ(windowed.replicas[0].switch_on, 20.0);  // cycle 0 counts the switch-ons inside the window
  EXPECT_EQ(windowed.replicas[0].switch_off, 27.0);
  EXPECT_EQ(second.replicas[0].switch_on, 20.0);
  // the reference segment is the window's field-off frames before the switch-on: t = 15 … 19.5
  EXPECT_EQ(windowed.replicas[0].reference_frames, 10u);
  EXPECT_NEAR(windowed.curve_time.front(), -5.0, 1e-12);  // time since the switch-on, from the window's first frame
  // a window without a switch-on inside
  EXPECT_THROW(analyse(anisodyn::testing_support::time_window(28.0, std::nullopt), 0), InputError);
}

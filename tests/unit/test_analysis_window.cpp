// The time window every analysis stage takes (frame_window.hpp, trajectory.cpp), on synthetic H5MD
// files: the frames kept (inclusive bounds, open ends, stride, a decimal bound on a binary time),
// the strided hyperslab read against the full read, observables windowed by time (event lists
// keeping the state in force), the replicas' common grid choosing the same frames for all, the
// replica checks limited to the windowed frames, and the errors (too few frames, from ≥ to,
// stride < 1, unknown keys, the refused frame keys of the past).
#include <gtest/gtest.h>

#include "anisodyn/analysis/frame_window.hpp"
#include "anisodyn/analysis/trajectory.hpp"
#include "anisodyn/io/h5md.hpp"
#include "input_error.hpp"
#include "scratch_dir.hpp"
#include "synthetic_trajectory.hpp"
#include "time_window.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;
using anisodyn::testing_support::gaussian_walks;
using anisodyn::testing_support::input_error;
using anisodyn::testing_support::linear_times;
using anisodyn::testing_support::SyntheticTrajectory;
using anisodyn::testing_support::time_window;

namespace {

TrajectoryNeeds positions_in(const FrameWindow& w) {
  TrajectoryNeeds n;
  n.positions = true;
  n.window = w;
  return n;
}

class WindowTest : public anisodyn::testing_support::ScratchDirTest {
 protected:
  WindowTest() : ScratchDirTest("window") {}

  /// 10 walkers, frames at t = 0, 1, …, 19.
  std::string walk(const std::string& name, unsigned seed, const std::vector<double>& time = linear_times(20, 1.0)) {
    const std::string p = file(name);
    gaussian_walks(10, time, Vec3(0.5, 0.5, 0.5), seed).write(p);
    return p;
  }
};

std::vector<std::size_t> indices(const Trajectory& t) { return t.frame_index; }

}  // namespace

TEST_F(WindowTest, KeepsTheFramesInsideInclusiveBounds) {
  const std::string p = walk("w.h5", 1);
  const Trajectory all = load_trajectory(p, positions_in(FrameWindow{}));
  const Trajectory t = load_trajectory(p, positions_in(time_window(2.0, 5.0)));
  ASSERT_EQ(t.frames, 4u);
  EXPECT_EQ(indices(t), (std::vector<std::size_t>{2, 3, 4, 5}));
  EXPECT_EQ(t.time, (std::vector<double>{2, 3, 4, 5}));
  EXPECT_EQ(t.step, (std::vector<std::int64_t>{2, 3, 4, 5}));
  for (std::size_t f = 0; f < t.frames; ++f)
    for (std::size_t i = 0; i < t.particles; ++i) EXPECT_EQ(t.pos(f, i), all.pos(f + 2, i));
}

TEST_F(WindowTest, OpenEndsAndStride) {
  const std::string p = walk("w.h5", 2);
  EXPECT_EQ(indices(load_trajectory(p, positions_in(time_window(std::nullopt, 3.0)))), (std::vector<std::size_t>{0, 1, 2, 3}));
  EXPECT_EQ(indices(load_trajectory(p, positions_in(time_window(17.0, std::nullopt)))), (std::vector<std::size_t>{17, 18, 19}));
  // every 3rd frame of the window, from its first: 1, 4, 7, 10 (13 is past the end 11.5)
  const Trajectory all = load_trajectory(p, positions_in(FrameWindow{}));
  const Trajectory t = load_trajectory(p, positions_in(time_window(0.5, 11.5, 3)));
  EXPECT_EQ(indices(t), (std::vector<std::size_t>{1, 4, 7, 10}));
  for (std::size_t k = 0; k < t.frames; ++k) {
    EXPECT_EQ(t.time[k], all.time[1 + 3 * k]);
    EXPECT_EQ(t.pos(k, 9), all.pos(1 + 3 * k, 9));
    EXPECT_EQ(t.box_edges(k), all.box_edges(1 + 3 * k));
  }
}

TEST_F(WindowTest, ADecimalBoundCatchesTheFrameStoredAtThatTime) {
  std::vector<double> time;
  for (int k = 0; k < 10; ++k) time.push_back(k * 0.1);  // 0.30000000000000004 is frame 3
  const std::string p = walk("w.h5", 3, time);
  EXPECT_EQ(indices(load_trajectory(p, positions_in(time_window(0.3, 0.6)))), (std::vector<std::size_t>{3, 4, 5, 6}));
}

TEST_F(WindowTest, StridedReaderMatchesTheFullRead) {
  const std::string p = walk("w.h5", 4);
  io::H5mdReader r(p);
  std::size_t width = 0;
  const auto full = r.read_element_frames("position", width);
  const auto some = r.read_element_frames("position", width, io::FrameSlice{2, 4, 5});  // frames 2, 7, 12, 17
  ASSERT_EQ(some.size(), 4u * 10u * 3u);
  for (std::size_t k = 0; k < 4; ++k)
    for (std::size_t j = 0; j < 30; ++j) EXPECT_EQ(some[30 * k + j], full[30 * (2 + 5 * k) + j]);
  const auto ids = r.read_integer_element_frames("id", io::FrameSlice{19, 1, 1});
  EXPECT_EQ(ids.size(), 10u);
  const InputError e = input_error([&] { r.read_element_frames("position", width, io::FrameSlice{15, 2, 5}); });
  EXPECT_NE(std::string(e.what()).find("requested"), std::string::npos) << e.what();
}

TEST_F(WindowTest, ObservablesAreWindowedByTimeAndEventListsKeepTheStateInForce) {
  SyntheticTrajectory s = gaussian_walks(4, linear_times(20, 1.0), Vec3(1, 1, 1), 5);
  std::vector<std::pair<double, std::vector<double>>> series, switches;
  for (int k = 0; k < 40; ++k) series.push_back({0.5 * k, {static_cast<double>(k)}});
  switches = {{0.0, {0, 1, 0, 0}}, {3.0, {1, 1, 0, 0}}, {7.0, {0, 1, 0, 0}}, {12.0, {1, 1, 0, 0}}};
  s.observables = {{"series", series}, {"field_switches", switches}};
  const std::string p = file("obs.h5");
  s.write(p);
  TrajectoryNeeds n = positions_in(time_window(4.0, 10.0, 3));
  n.observables = {"series"};
  n.event_observables = {"field_switches"};
  const Trajectory t = load_trajectory(p, n);
  EXPECT_EQ(indices(t), (std::vector<std::size_t>{4, 7, 10}));
  // a sampled series: every row with 4 ≤ t ≤ 10 (the stride thins frames, not observable rows)
  const ObservableSeries& o = t.observables.at("series");
  ASSERT_EQ(o.time.size(), 13u);
  EXPECT_EQ(o.time.front(), 4.0);
  EXPECT_EQ(o.time.back(), 10.0);
  EXPECT_EQ(o.value.front(), 8.0);
  // an event list: the switch-on at t = 3 is the state in force at t = 4, then the switch-off at 7
  const ObservableSeries& sw = t.observables.at("field_switches");
  EXPECT_EQ(sw.time, (std::vector<double>{3.0, 7.0}));
  EXPECT_EQ(sw.value[0], 1.0);
  EXPECT_EQ(sw.value[4], 0.0);
}

TEST_F(WindowTest, ReplicasShareTheFramesChosenOnTheCommonGrid) {
  // replica b's clock runs 2% fast: its frame 10 is at 10.2, replica a's at 10.0; the grid's at 10.1
  std::vector<double> fast;
  for (double t : linear_times(20, 1.0)) fast.push_back(1.02 * t);
  const std::vector<std::string> paths{walk("a.h5", 6), walk("b.h5", 7, fast)};
  TrajectoryNeeds n = positions_in(time_window(4.05, 10.15));
  std::vector<std::vector<std::size_t>> seen;
  FrameSelection selected;
  const auto grid = for_each_replica(paths, n, [&](const Trajectory& t, std::size_t) { seen.push_back(t.frame_index); }, 0.05, &selected);
  // grid times 1.01 k: frames 5 … 10 (4.04 is outside, 10.1 inside), the same for both replicas
  const std::vector<std::size_t> expected{5, 6, 7, 8, 9, 10};
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0], expected);
  EXPECT_EQ(seen[1], expected);
  EXPECT_EQ(selected.frames.first, 5u);
  EXPECT_EQ(selected.frames.count, 6u);
  ASSERT_EQ(grid.size(), 6u);
  EXPECT_NEAR(grid.front(), 5.05, 1e-12);
  const nlohmann::json record = n.window.record(selected.frames, selected.grid);
  EXPECT_EQ(record["frames"], 6);
  EXPECT_EQ(record["first_frame"], 5);
  EXPECT_EQ(record["last_frame"], 10);
  EXPECT_NEAR(record["last_time"].get<double>(), 10.1, 1e-12);
}

TEST_F(WindowTest, ReplicaTimesAreComparedOnTheWindowedFramesOnly) {
  // replica b agrees with a up to t = 9, then jumps 5 τ ahead (a clock fault after the window)
  std::vector<double> late = linear_times(20, 1.0);
  for (std::size_t f = 10; f < late.size(); ++f) late[f] += 5.0;
  const std::vector<std::string> paths{walk("a.h5", 8), walk("b.h5", 9, late)};
  auto visit = [](const Trajectory&, std::size_t) {};
  const InputError e = input_error([&] { for_each_replica(paths, positions_in(FrameWindow{}), visit); });
  EXPECT_NE(std::string(e.what()).find("mismatched replicas"), std::string::npos) << e.what();
  EXPECT_NO_THROW(for_each_replica(paths, positions_in(time_window(std::nullopt, 9.5)), visit));
  // the tolerance is relative to the time up to the last windowed frame: 0.3 τ apart at t = 4 is
  // within 5% of 19 τ but not of 4 τ
  std::vector<double> shifted = linear_times(20, 1.0);
  for (std::size_t f = 1; f < shifted.size(); ++f) shifted[f] += 0.3;
  const std::vector<std::string> near{walk("c.h5", 10), walk("d.h5", 11, shifted)};
  EXPECT_NO_THROW(for_each_replica(near, positions_in(FrameWindow{}), visit));
  EXPECT_THROW(for_each_replica(near, positions_in(time_window(std::nullopt, 4.2)), visit), InputError);
}

TEST_F(WindowTest, AWindowWithTooFewFramesNamesTheWindowAndTheFile) {
  const std::string p = walk("w.h5", 12);
  TrajectoryNeeds n = positions_in(time_window(2.2, 2.8));
  const InputError none = input_error([&] { for_each_replica({p}, n, [](const Trajectory&, std::size_t) {}); });
  EXPECT_EQ(none.file(), "stage.json");
  EXPECT_EQ(none.json_path(), "window");
  const std::string msg = none.what();
  EXPECT_NE(msg.find("from: 2.2"), std::string::npos) << msg;
  EXPECT_NE(msg.find(p), std::string::npos) << msg;
  EXPECT_NE(msg.find("selects 0 frame(s)"), std::string::npos) << msg;
  n.window = time_window(2.0, 2.8);
  n.min_frames = 2;  // one frame, a lag needs two
  const InputError one = input_error([&] { load_trajectory(p, n); });
  EXPECT_NE(std::string(one.what()).find("needs at least 2"), std::string::npos) << one.what();
}

TEST(FrameWindowConfig, ParsesAndRefusesBadWindows) {
  auto parse = [](const nlohmann::json& j) {
    tool::ConfigNode cfg(j, "stage.json");
    FrameWindow w = parse_frame_window(cfg);
    cfg.finish();
    return w;
  };
  EXPECT_FALSE(parse(nlohmann::json::object()).given);
  const FrameWindow w = parse({{"window", {{"from", 1.5}, {"stride", 4}}}});
  EXPECT_TRUE(w.given);
  EXPECT_EQ(*w.from, 1.5);
  EXPECT_FALSE(w.to.has_value());
  EXPECT_EQ(w.stride, 4u);
  EXPECT_EQ(input_error([&] { parse({{"window", {{"from", 5}, {"to", 5}}}}); }).json_path(), "window.to");
  EXPECT_EQ(input_error([&] { parse({{"window", {{"from", 5}, {"to", 2}}}}); }).json_path(), "window.to");
  EXPECT_EQ(input_error([&] { parse({{"window", {{"stride", 0}}}}); }).json_path(), "window.stride");
  const InputError unknown = input_error([&] { parse({{"window", {{"form", 1}}}}); });
  EXPECT_NE(std::string(unknown.what()).find("form"), std::string::npos) << unknown.what();
  EXPECT_EQ(unknown.file(), "stage.json");
  tool::ConfigNode old({{"frames", {{"first", 2}}}}, "stage.json");
  const InputError refused = input_error([&] { refuse_frame_key(old, "frames"); });
  EXPECT_EQ(refused.json_path(), "frames");
  EXPECT_NE(std::string(refused.what()).find("window"), std::string::npos);
}

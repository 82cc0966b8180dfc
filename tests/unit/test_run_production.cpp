// The shared production runner (run/): schedule, frame rules, observation cadence, field switches
// and checkpoint/restore, driven by a scripted client whose step covers a known time; and the one
// field schema (docs/run.md) as MC and DMC read it.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "anisodyn/io/h5md.hpp"
#include "anisodyn/mc/protocol_config.hpp"
#include "anisodyn/run/field_config.hpp"
#include "anisodyn/run/production_runner.hpp"
#include "input_error.hpp"
#include "scratch_dir.hpp"

using namespace anisodyn;
using anisodyn::testing_support::input_error;

namespace {

/// Steps of 0.25 time units; moves particle 0 by one unit along x per step; observes the number of
/// steps since its previous row.
class ScriptedClient : public run::ProductionClient {
 public:
  explicit ScriptedClient(State& s) : state_(s) {}
  double advance() override {
    Vec3 r = state_.particles.position(0) + Vec3(1, 0, 0);
    Int3 image = state_.particles.image(0);
    state_.box.wrap(r, image);
    state_.particles.set_position(0, r);
    state_.particles.set_image(0, image);
    ++since_row_;
    return 0.25;
  }
  void observe(io::H5mdWriter& out, std::int64_t step, double time) override {
    out.append_observable("steps_in_row", step, time, static_cast<double>(since_row_));
    since_row_ = 0;
  }
  Vec3 switch_field(bool on, std::int64_t) override {
    on_ = on;
    return Vec3(0, 0, 1);
  }
  bool field_on() const override { return on_; }
  int since_row_ = 0;  // part of the client's own checkpoint

 private:
  State& state_;
  bool on_ = false;
};

State two_spheres() {
  State s;
  s.box = Box(Vec3(10, 10, 10));
  s.species = {Species{"ball", Shape::sphere(1.0), 1.0, Vec3::Ones(), Vec3::Zero()}};
  s.particles.add(0, Vec3(1, 1, 1), Quat::Identity(), 0);
  s.particles.add(0, Vec3(5, 5, 5), Quat::Identity(), 1);
  return s;
}

run::ProductionSettings settings_from(const nlohmann::json& j) {
  tool::ConfigNode cfg(j, "run.json");
  run::ProductionSettings s;
  s.unit = run::StepUnit::steps();
  s.schedule = run::parse_schedule(cfg, s.unit, false);
  s.frames = run::parse_frame_rules(cfg, s.unit);
  s.observe_every = cfg.positive_integer("observe_every", 1);
  cfg.finish();
  return s;
}

io::H5mdHeader header(const State& s) { return io::H5mdHeader{"anisodyn", "", "test", {}, {}, s.species}; }

/// Runs a fresh client from `state` to the end into `path`; returns the runner's final cursor.
nlohmann::json run_to_end(const std::string& path, State& state, const run::ProductionSettings& settings) {
  ScriptedClient client(state);
  run::ProductionRunner runner(state, client, settings, true);
  run::CheckpointClock never(0, {});
  io::H5mdWriter out(path, header(state));
  runner.run(out, never, 0);
  out.commit();
  return runner.checkpoint_state();
}

class RunProduction : public testing_support::ScratchDirTest {
 protected:
  RunProduction() : ScratchDirTest("run-production") {}
};

}  // namespace

TEST_F(RunProduction, SegmentsFramesAndObservationsFollowTheSchedule) {
  // 10 steps off, then 2 time units (8 steps of 0.25) on; frames every 4 steps and 3 steps after
  // each switch, every step for the first 2; a row every 3 steps.
  const auto settings = settings_from({{"schedule", {{"segments", {{{"field", "off"}, {"steps", 10}}, {{"field", "on"}, {"time", 2.0}}}}}},
                                       {"frames", {{"every_steps", 4}, {"after_switch", {{"every_steps", 1}, {"for_steps", 2}}}}},
                                       {"observe_every", 3}});
  State state = two_spheres();
  const nlohmann::json end = run_to_end(file("traj.h5"), state, settings);
  EXPECT_EQ(end["step"], 18);
  EXPECT_DOUBLE_EQ(end["time"].get<double>(), 4.5);
  EXPECT_EQ(state.step, 18);
  ASSERT_EQ(end["switches"].size(), 2u);
  EXPECT_EQ(end["switches"][1]["step"], 10);
  EXPECT_EQ(end["switches"][1]["field"], "on");

  const io::H5mdReader r(file("traj.h5"));
  // start; every 4; 1, 2 after the start (switch at 0) and 11, 12 after the switch at 10; the end.
  EXPECT_EQ(r.frame_steps(), (std::vector<std::int64_t>{0, 1, 2, 4, 8, 11, 12, 16, 18}));
  const auto rows = r.read_observable("steps_in_row");
  EXPECT_EQ(rows.step, (std::vector<std::int64_t>{3, 6, 9, 12, 15, 18}));
  for (double v : rows.value) EXPECT_EQ(v, 3.0);
  const auto switches = r.read_observable("field_switches");
  EXPECT_EQ(switches.step, (std::vector<std::int64_t>{0, 10}));
  EXPECT_EQ(switches.value, (std::vector<double>{0, 0, 0, 1, 1, 0, 0, 1}));
  // Particle 0 moved one unit per step: 18 steps from x = 1 is x = 9 (no wrap) at the last frame.
  EXPECT_DOUBLE_EQ(r.read_frame(-1).particles.x[0], 9.0);
}

TEST_F(RunProduction, ALastRowCoversTheStepsAfterThePreviousOne) {
  const auto settings = settings_from({{"steps", 7}, {"observe_every", 3}});
  State state = two_spheres();
  run_to_end(file("traj.h5"), state, settings);
  const io::H5mdReader r(file("traj.h5"));
  const auto rows = r.read_observable("steps_in_row");
  EXPECT_EQ(rows.step, (std::vector<std::int64_t>{3, 6, 7}));
  EXPECT_EQ(rows.value, (std::vector<double>{3, 3, 1}));
  EXPECT_EQ(r.frame_steps(), (std::vector<std::int64_t>{0, 7}));
}

TEST_F(RunProduction, ACheckpointedRunResumesToTheSameCursor) {
  // Checkpoints every 5 steps (3 more steps of an earlier stage count towards the cadence); the
  // runner state saved at the checkpoint after step 7, restored into a fresh runner, continues to
  // the same end, switches and frame clock as the uninterrupted run.
  const nlohmann::json cfg = {{"time", 6.0}, {"schedule", {{"switches", {{{"time", 1.0}, {"field", "on"}}, {{"time", 3.0}, {"field", "off"}}}}}},
                              {"frames", {{"every_time", 1.1}, {"log_first_time", 0.5}, {"log_per_decade", 3}}}};
  const auto settings = settings_from(cfg);

  State a = two_spheres();
  ScriptedClient ca(a);
  run::ProductionRunner full(a, ca, settings, true);
  std::vector<nlohmann::json> saved;
  std::vector<State> saved_states;
  run::CheckpointClock every5(5, [&] { saved.push_back(full.checkpoint_state()); saved_states.push_back(a); });
  {
    io::H5mdWriter out(file("full.h5"), header(a));
    full.run(out, every5, 3);
    out.commit();
  }
  ASSERT_GE(saved.size(), 2u);
  EXPECT_EQ(saved[0]["step"], 2);  // 3 + 2 = 5
  EXPECT_EQ(saved[1]["step"], 7);

  State b = saved_states[1];
  ScriptedClient cb(b);
  cb.switch_field(true, 0);  // the client's own state at that point (field on between t = 1 and 3)
  run::ProductionRunner resumed(b, cb, settings, true);
  resumed.restore(saved[1]);
  EXPECT_EQ(b.step, 7);
  run::CheckpointClock never(0, {});
  {
    io::H5mdWriter out(file("resumed.h5"), header(b));
    resumed.run(out, never, 3);
    out.commit();
  }
  EXPECT_EQ(resumed.checkpoint_state(), full.checkpoint_state());
  EXPECT_EQ(b.particles.x, a.particles.x);
  // Frames after step 7 are the same in both runs.
  std::vector<std::int64_t> tail_full;
  for (auto s : io::H5mdReader(file("full.h5")).frame_steps()) if (s > 7) tail_full.push_back(s);
  EXPECT_EQ(io::H5mdReader(file("resumed.h5")).frame_steps(), tail_full);
  EXPECT_FALSE(tail_full.empty());
}

TEST(RunFieldSchema, McTakesTheSharedFormOnly) {
  auto mc = [](const nlohmann::json& field) {
    nlohmann::json j = {{"field", field}, {"phases", {{{"type", "nvt"}, {"cycles", 10}}}}};
    tool::ConfigNode cfg(j, "mc.json");
    McProtocol p = parse_mc_protocol(cfg);
    cfg.finish();
    return p;
  };
  const McProtocol p = mc({{"direction", {0, 2, 0}}, {"orientational", {{"strength", 3.0}, {"axis", "L"}}}});
  EXPECT_EQ(p.field.strength, 3.0);
  EXPECT_EQ(p.field.body_axis, 2);
  EXPECT_EQ(p.field.direction, Vec3(0, 1, 0));
  // The former MC form is read nowhere: its keys are unknown.
  EXPECT_EQ(input_error([&] { mc({{"strength", 3.0}, {"axis", "W"}}); }).json_path(), "field");
  EXPECT_EQ(input_error([&] { mc({{"orientational", {{"strength", 1.0}}}, {"strength", 3.0}}); }).json_path(), "field.strength");
  // Parts MC does not have are errors by name.
  EXPECT_EQ(input_error([&] { mc({{"orientational", {{"strength", 1.0}}}, {"dipoles", {{"gamma", 1.0}, {"species", {"a"}}}}}); }).json_path(),
            "field.dipoles");
  EXPECT_EQ(input_error([&] { mc({{"orientational", {{"strength", 1.0}}}, {"initially", "on"}}); }).json_path(), "field.initially");
  EXPECT_EQ(input_error([&] { mc({{"orientational", {{"strength", -1.0}}}}); }).json_path(), "field.orientational.strength");
}

TEST(RunFieldSchema, StepUnitsNameTheKeys) {
  // A time-stepping engine counts steps: "cycles" is then an unknown key.
  EXPECT_EQ(input_error([] { settings_from({{"cycles", 10}}); }).json_path(), "steps");
  const auto s = settings_from({{"steps", 100}, {"schedule", {{"switches", {{{"step", 40}, {"field", "on"}}}}}}});
  ASSERT_EQ(s.schedule.size(), 2u);
  EXPECT_EQ(s.schedule[0].length, 40.0);
  EXPECT_FALSE(s.schedule[0].field_on);
  EXPECT_TRUE(s.schedule[1].field_on);
  EXPECT_EQ(s.schedule[1].length, 100.0);
  EXPECT_EQ(input_error([] { settings_from({{"steps", 100}, {"schedule", {{"switches", {{{"cycle", 40}, {"field", "on"}}}}}}}); }).json_path(),
            "schedule.switches[0]");
}

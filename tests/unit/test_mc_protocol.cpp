// MC protocol phases: quick compression and the NPT ramp + squeeze both land exactly on the target
// packing fraction with no overlaps; the squeeze adapts its step to dense fluids and resumes bit
// for bit; an interrupt during quick compression's overlap removal goes
// back to the last configuration without overlaps, and the run resumed from there ends as an
// uninterrupted one, bit for bit.
#include <gtest/gtest.h>

#include <csignal>
#include <tuple>

#include "anisodyn/config/builder.hpp"
#include "anisodyn/core/error.hpp"
#include "anisodyn/core/signals.hpp"
#include "anisodyn/mc/protocol.hpp"
#include "scratch_dir.hpp"

using namespace anisodyn;

namespace {
State lattice(const Species& sp, std::size_t n, double eta, bool random_orientation) {
  State s;
  s.species = {sp};
  s.box = Box(box_edges_for_packing_fraction(s.species, {n}, eta, Vec3::Ones()));
  OrientationRule rule;
  rule.mode = random_orientation ? OrientationRule::Mode::Random : OrientationRule::Mode::Aligned;
  Rng rng(9, 9);
  place_on_lattice(s, PlacementRequest{{n}, {rule}, 1000}, rng);
  return s;
}

McPhase compress(double eta, const std::string& method) {
  McPhase p;
  p.type = McPhase::Type::Compress;
  p.target_packing_fraction = eta;
  p.method = method;
  p.tune = true;
  p.max_cycles = 40000;
  return p;
}

struct Checkpoint {
  Particles particles;
  Box box;
  nlohmann::json runner;
};

class McProtocolRun : public testing_support::ScratchDirTest {
 protected:
  McProtocolRun() : ScratchDirTest("mc-protocol") {}
  /// Runs the protocol on `s`; the trajectory goes to a scratch file.
  void run(State& s, const McProtocol& proto) {
    McRunner runner(s, proto, true);
    io::H5mdWriter out(file("mc.h5"), {"anisodyn", "", "test", nlohmann::json::object(), nlohmann::json::object(), s.species});
    runner.run(out, 0, [] {});
  }
  /// The run of `proto` on `start` resumed from checkpoint `c` and run to its end.
  State resumed_from(const State& start, const McProtocol& proto, const Checkpoint& c) {
    State resumed = start;
    resumed.particles = c.particles;
    resumed.box = c.box;
    McRunner again(resumed, proto, true);
    again.restore(c.runner);
    io::H5mdWriter out(file("resumed.h5"), {"anisodyn", "", "test", nlohmann::json::object(), nlohmann::json::object(), resumed.species});
    again.run(out, 0, [] {});
    return resumed;
  }
};
}  // namespace

TEST_F(McProtocolRun, QuickCompressionOfHardSpheresLandsOnTheTargetWithoutOverlaps) {
  State s = lattice(Species{"hs", Shape::sphere(1.0), 1.0, {}, {}}, 256, 0.20, false);
  McProtocol proto;
  proto.phases = {compress(0.40, "quick")};
  run(s, proto);
  EXPECT_NEAR(s.packing_fraction(), 0.40, 1e-12);
  EXPECT_FALSE(HardOverlap(s).first_overlap().has_value());
}

TEST_F(McProtocolRun, QuickCompressionOfRandomBoards) {
  State s = lattice(Species{"board", Shape::cuboid(1.0, 3.4641, 12.0), 1.0, {}, {}}, 120, 0.01, true);
  McProtocol proto;
  proto.phases = {compress(0.12, "quick")};
  run(s, proto);
  EXPECT_NEAR(s.packing_fraction(), 0.12, 1e-12);
  EXPECT_FALSE(HardOverlap(s).first_overlap().has_value());
}

TEST_F(McProtocolRun, NptCompressionLandsExactlyOnTheTarget) {
  State s = lattice(Species{"hs", Shape::sphere(1.0), 1.0, {}, {}}, 216, 0.10, false);
  McProtocol proto;
  proto.phases = {compress(0.30, "npt")};
  run(s, proto);
  EXPECT_NEAR(s.packing_fraction(), 0.30, 1e-12);
  EXPECT_FALSE(HardOverlap(s).first_overlap().has_value());
}

TEST_F(McProtocolRun, TheSqueezeHalvesItsStepUntilStepsSucceedAndResumesBitForBit) {
  // 500 hard spheres melted at η = 0.44, then squeezed by 1.1% in volume to 0.445. A 0.1% step
  // succeeds with a chance of about exp[−(βPV − N) × 10⁻³] ≈ 2% here (βPV ≈ 8.8 N), so fixed steps
  // would need about 2700 cycles; halved steps need a few hundred. A run resumed from a checkpoint
  // taken in the middle of the squeeze (cursor and step included) ends as the uninterrupted one.
  const State start = lattice(Species{"hs", Shape::sphere(1.0), 1.0, {}, {}}, 500, 0.44, false);
  McProtocol proto;
  McPhase melt;
  melt.type = McPhase::Type::Nvt;
  melt.cycles = 300;
  melt.tune = true;
  proto.phases = {melt, compress(0.445, "npt")};
  proto.phases[1].squeeze_window = 0.05;  // squeeze only
  proto.phases[1].max_cycles = 1200;
  State reference = start;
  run(reference, proto);
  EXPECT_NEAR(reference.packing_fraction(), 0.445, 1e-12);
  EXPECT_FALSE(HardOverlap(reference).first_overlap().has_value());

  std::vector<Checkpoint> mid_squeeze;
  State s = start;
  {
    McRunner runner(s, proto, true);
    io::H5mdWriter out(file("checkpointed.h5"), {"anisodyn", "", "test", nlohmann::json::object(), nlohmann::json::object(), s.species});
    runner.run(out, 29, [&] {
      const nlohmann::json js = runner.checkpoint_state();
      const auto& cursor = js.at("cursor");
      if (cursor.at("squeezing").get<bool>() && cursor.at("squeeze_step").get<double>() < 1e-3)
        mid_squeeze.push_back({s.particles, s.box, js});
    });
  }
  EXPECT_EQ(s.particles.x, reference.particles.x);
  ASSERT_GE(mid_squeeze.size(), 2u);
  const Checkpoint& c = mid_squeeze[mid_squeeze.size() / 2];
  EXPECT_GT(c.box.volume(), reference.box.volume());
  const State resumed = resumed_from(start, proto, c);
  EXPECT_EQ(resumed.box.edges(), reference.box.edges());
  EXPECT_EQ(resumed.particles.x, reference.particles.x);
  EXPECT_EQ(resumed.particles.z, reference.particles.z);
}

TEST_F(McProtocolRun, AnInterruptDuringOverlapRemovalGoesBackAndResumesToTheSameResult) {
  // 300 random rods 12×1×1 quick-compressed from η = 0.02 to 0.15, one ordinary sweep per shrink,
  // checkpoints as often as they may be (before each shrink). The interrupt is requested while the
  // third is written: the next shrink's first removal (or squeeze) cycle must honour it by going
  // back to that third checkpoint's configuration and cursor.
  State start;
  start.species = {Species{"rod", Shape::cuboid(1.0, 1.0, 12.0), 1.0, {}, {}}};
  start.box = Box(box_edges_for_packing_fraction(start.species, {300}, 0.02, Vec3::Ones()));
  Rng placement(5, 0);
  insert_randomly(start, PlacementRequest{{300}, {OrientationRule{OrientationRule::Mode::Random}}, 100000}, placement);
  McProtocol proto;
  proto.phases = {compress(0.15, "quick")};
  proto.phases[0].squeeze_sweeps = 1;
  State reference = start;
  run(reference, proto);

  std::vector<Checkpoint> written;
  State s = start;
  install_interrupt_handlers();
  {
    McRunner runner(s, proto, true);
    io::H5mdWriter out(file("interrupted.h5"), {"anisodyn", "", "test", nlohmann::json::object(), nlohmann::json::object(), s.species});
    const auto checkpoint = [&] {
      EXPECT_FALSE(HardOverlap(s).first_overlap().has_value()) << "checkpoint " << written.size() << " holds overlaps";
      written.push_back({s.particles, s.box, runner.checkpoint_state()});
      if (written.size() == 3) std::raise(SIGINT);
    };
    EXPECT_THROW(runner.run(out, 1, checkpoint), Interrupted);
  }
  ASSERT_TRUE(interrupt_requested());
  clear_interrupt_request();
  ASSERT_EQ(written.size(), 4u);
  EXPECT_EQ(written[3].box.edges(), written[2].box.edges());
  EXPECT_EQ(written[3].particles.x, written[2].particles.x);
  EXPECT_EQ(written[3].particles.qw, written[2].particles.qw);
  EXPECT_EQ(written[3].runner, written[2].runner);
  EXPECT_GT(written[3].box.volume(), reference.box.volume());

  const State resumed = resumed_from(start, proto, written[3]);
  EXPECT_EQ(resumed.box.edges(), reference.box.edges());
  EXPECT_EQ(resumed.particles.x, reference.particles.x);
  EXPECT_EQ(resumed.particles.y, reference.particles.y);
  EXPECT_EQ(resumed.particles.z, reference.particles.z);
  EXPECT_EQ(resumed.particles.qw, reference.particles.qw);
  EXPECT_EQ(resumed.particles.qz, reference.particles.qz);
}

TEST_F(McProtocolRun, DomainSweepPhasesRunInBatchesWithTheBitsOfSingleCycles) {
  // Phases under domain sweeps run several cycles as one batch, stopping wherever anything reads
  // the state: observations (every 3 cycles), frames (every 7), tuning (every 20), checkpoints. A
  // checkpoint due every cycle forbids batches, so that run is the cycle-by-cycle reference;
  // another with checkpoints every 4 cycles batches between them. The NPT phase makes each cut's
  // volume moves at its end; a run resumed from a checkpoint in the middle of a cut, with moves
  // owed, ends as the others.
  State start = lattice(Species{"rod", Shape::cuboid(1.0, 1.0, 12.0), 1.0, {}, {}}, 300, 0.25, false);
  McProtocol proto;
  proto.domain_sweeps = true;
  proto.observe_every = 3;
  proto.tune_every = 20;
  proto.frames.every_steps = 7;
  McPhase tuned;
  tuned.type = McPhase::Type::Nvt;
  tuned.label = "tuned";
  tuned.cycles = 47;
  tuned.tune = true;
  McPhase sampled = tuned;
  sampled.label = "sampled";
  sampled.cycles = 31;
  sampled.tune = false;
  McPhase npt = sampled;
  npt.type = McPhase::Type::Npt;
  npt.label = "npt";
  npt.cycles = 29;
  npt.pressure = 0.05;
  proto.phases = {tuned, sampled, npt};
  std::optional<Checkpoint> owing;  // the first checkpoint of the NPT phase that owes volume moves
  auto run_with_checkpoints = [&](std::int64_t every, const std::string& name) {
    State s = start;
    McRunner runner(s, proto, true);
    io::H5mdWriter out(file(name), {"anisodyn", "", "test", nlohmann::json::object(), nlohmann::json::object(), s.species});
    int written = 0;
    runner.run(out, every, [&] {
      ++written;
      const nlohmann::json js = runner.checkpoint_state();
      if (!owing && js.at("cursor").at("phase") == 2 && js.at("volume_moves_owed").get<int>() > 0) owing = Checkpoint{s.particles, s.box, js};
    });
    return std::make_tuple(s.particles, runner.summary(), runner.checkpoint_state(), written, s.box);
  };
  const auto [single, single_summary, single_engine, single_checkpoints, single_box] = run_with_checkpoints(1, "single.h5");
  for (const std::int64_t every : {std::int64_t{0}, std::int64_t{4}}) {
    const auto [batched, summary, engine, checkpoints, box] = run_with_checkpoints(every, "batched.h5");
    EXPECT_EQ(batched.x, single.x) << "checkpoints every " << every;
    EXPECT_EQ(batched.y, single.y);
    EXPECT_EQ(batched.qw, single.qw);
    EXPECT_EQ(batched.qz, single.qz);
    EXPECT_EQ(box.edges(), single_box.edges());
    EXPECT_EQ(summary, single_summary);
    EXPECT_EQ(engine, single_engine);
    EXPECT_EQ(checkpoints, every == 0 ? 0 : 107 / 4);
  }
  EXPECT_EQ(single_checkpoints, 107);
  EXPECT_NE(single.x, start.particles.x);
  EXPECT_NE(single_box.edges(), start.box.edges());
  ASSERT_TRUE(owing.has_value());
  const State resumed = resumed_from(start, proto, *owing);
  EXPECT_EQ(resumed.box.edges(), single_box.edges());
  EXPECT_EQ(resumed.particles.x, single.x);
  EXPECT_EQ(resumed.particles.qw, single.qw);
}

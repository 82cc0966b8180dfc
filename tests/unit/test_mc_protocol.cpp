// MC protocol phases: quick compression and the NPT ramp + squeeze both land exactly on the target
// packing fraction with no overlaps.
#include <gtest/gtest.h>

#include "anisodyn/config/builder.hpp"
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

class McProtocolRun : public testing_support::ScratchDirTest {
 protected:
  McProtocolRun() : ScratchDirTest("mc-protocol") {}
  /// Runs the protocol on `s`; the trajectory goes to a scratch file.
  void run(State& s, const McProtocol& proto) {
    McRunner runner(s, proto, true);
    io::H5mdWriter out(file("mc.h5"), {"anisodyn", "", "test", nlohmann::json::object(), nlohmann::json::object(), s.species});
    runner.run(out, 0, [] {});
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

// DmcRunner bookkeeping around the preliminary balancing run of a pulled tracer:
//  - the per-particle accumulators count from production's t = 0, so the summary's displacement
//    along the force equals the tracer's displacement between the first and the last frame, and
//    its drift velocity divides production displacement by production time;
//  - the realised-balance observable, with the lone tracer as the reference and one cycle per row
//    (rows in which the tracer has E = 0 or no trial at all), is NaN there and finite and modest
//    elsewhere: never the ratio over a rounding residue.
#include <gtest/gtest.h>

#include <cmath>

#include "anisodyn/io/h5md.hpp"
#include "pulled_tracer_campaign.hpp"
#include "scratch_dir.hpp"

using namespace anisodyn;
using namespace anisodyn::testing_support;

namespace {

class DmcRunnerTracer : public ScratchDirTest {
 protected:
  DmcRunnerTracer() : ScratchDirTest("dmc-runner") {}
};

TEST_F(DmcRunnerTracer, AccumulatorsCountFromProductionStartAndTheBalanceObservableIsGuarded) {
  BathSystem bath;
  bath.lattice = 3;
  bath.box = 4.0;
  bath.mc_cycles = 200;
  const State start = tracer_in_bath(bath, 3);
  TracerRun r;
  r.pe = 5.0;
  r.tracer_dt = 0.001;
  r.preliminary_cycles = 3000;
  r.cycles = 3000;
  nlohmann::json config = tracer_config(r);
  config["observe_every"] = 1;
  State state = start;
  tool::ConfigNode cfg(config, "test.json");
  DmcProtocol protocol = parse_dmc_protocol(cfg);
  cfg.finish();
  DmcRunner runner(state, protocol, "test.json", true);
  const std::string path = file("run.h5");
  {
    io::H5mdWriter out(path, io::H5mdHeader{"anisodyn", "", "test", config, nlohmann::json::object(), state.species});
    runner.run(out, 0, [] {});
    out.commit();
  }
  const nlohmann::json& summary = runner.summary();
  ASSERT_TRUE(summary.contains("preliminary"));  // the preliminary stage ran and moved the tracer
  const io::H5mdReader in(path);
  const State first = in.read_frame(0), last = in.read_frame(-1);
  std::size_t tracer = 0;
  while (first.particles.species[tracer] != 1) ++tracer;
  const double z0 = first.box.unwrap(first.particles.position(tracer), first.particles.image(tracer)).z();
  const double z1 = last.box.unwrap(last.particles.position(tracer), last.particles.image(tracer)).z();
  const double along = summary.at("tracer").at("displacement_along_force").get<double>();
  EXPECT_NEAR(along, z1 - z0, 1e-9);
  EXPECT_GT(std::abs(z1 - z0), 0.0);
  EXPECT_DOUBLE_EQ(summary.at("tracer").at("drift_velocity").get<double>(), along / summary.at("time").get<double>());
  // Frame 0 is production's start: every accumulator is zero there.
  std::size_t width = 0;
  const std::vector<double> acc = in.read_element_frames("body_displacement", width);
  for (std::size_t k = 0; k < width * first.particles.size(); ++k) ASSERT_EQ(acc[k], 0.0);

  const auto balance = in.read_observable("balance");
  std::size_t undefined = 0, defined = 0;
  for (std::size_t row = 0; row < balance.step.size(); ++row) {
    const double bath_ratio = balance.value[row * balance.width + 0];
    if (std::isnan(bath_ratio)) {
      ++undefined;
      continue;
    }
    ++defined;
    // With n tracer trials in the row, a positive E_ref = (3·accepted − passed)/(2n) is at least 1/(2n),
    // so the bath's ratio is at most 2n·A_bath δt_bath/δt_tracer ≈ 2n; n exceeds 50 with
    // negligible probability at one expected trial per cycle.
    ASSERT_GT(bath_ratio, 0.0) << "row " << row;
    EXPECT_LT(std::abs(bath_ratio), 200.0) << "row " << row;
  }
  EXPECT_GT(undefined, 0u);  // rows without a tracer trial, or with E = 0, exist at one cycle per row
  EXPECT_GT(defined, 0u);
  EXPECT_TRUE(summary.at("species")[0].at("realised_balance").is_number());
  EXPECT_NEAR(summary.at("species")[0].at("realised_balance").get<double>(), 1.0, 0.2);
}

}  // namespace

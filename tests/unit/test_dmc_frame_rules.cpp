// DMC frame rules (docs/dmc.md): the logarithmic-in-cycles rule `frames.log_cycles` {per_decade,
// restart_every} against the set of frame cycles enumerated from its definition, and its parsing.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "anisodyn/dmc/dmc_protocol.hpp"
#include "input_error.hpp"

using namespace anisodyn;
using anisodyn::testing_support::input_error;

namespace {

/// The definition: m = 0 and round(10^(k/n)) for k = 0, 1, … up to `limit` cycles.
std::set<std::int64_t> log_cycles(double per_decade, std::int64_t limit) {
  std::set<std::int64_t> out{0};
  for (int k = 0;; ++k) {
    const std::int64_t m = std::llround(std::pow(10.0, k / per_decade));
    if (m > limit) break;
    out.insert(m);
  }
  return out;
}

DmcProtocol parse(const nlohmann::json& frames) {
  nlohmann::json j = {{"time_step", {{"board", 0.01}}}, {"cycles", 1000}, {"frames", frames}};
  tool::ConfigNode cfg(j, "dmc.json");
  DmcProtocol p = parse_dmc_protocol(cfg);
  cfg.finish();
  return p;
}

}  // namespace

TEST(DmcFrameRules, LogCyclesAfterEachSwitchMatchTheDefinition) {
  for (double per_decade : {5.0, 10.0, 2.5}) {
    run::FrameRules f;
    f.log_steps_per_decade = per_decade;
    const auto expected = log_cycles(per_decade, 100000);
    for (std::int64_t since = 0; since <= 100000; ++since)
      ASSERT_EQ(f.log_step_due(since), expected.count(since) > 0) << "per_decade " << per_decade << ", cycle " << since;
  }
  // 5 per decade, written out: 1, 2, 3, 4, 6, 10, 16, 25, 40, 63, 100 cycles after the switch
  run::FrameRules f;
  f.log_steps_per_decade = 5;
  std::vector<std::int64_t> due;
  for (std::int64_t since = 0; since <= 100; ++since)
    if (f.log_step_due(since)) due.push_back(since);
  EXPECT_EQ(due, (std::vector<std::int64_t>{0, 1, 2, 3, 4, 6, 10, 16, 25, 40, 63, 100}));
}

TEST(DmcFrameRules, LogCyclesRestartEveryBlock) {
  run::FrameRules f;
  f.log_steps_per_decade = 5;
  f.log_steps_restart = 50;
  const auto block = log_cycles(5, 49);
  for (std::int64_t since = 0; since < 1000; ++since) EXPECT_EQ(f.log_step_due(since), block.count(since % 50) > 0) << since;
  run::FrameRules off;  // the rule is off by default
  for (std::int64_t since = 0; since < 100; ++since) EXPECT_FALSE(off.log_step_due(since));
}

TEST(DmcFrameRules, LogCyclesAreParsedAndBadValuesNamed) {
  const DmcProtocol p = parse({{"every_cycles", 500}, {"log_cycles", {{"per_decade", 5}, {"restart_every", 2500}}}});
  EXPECT_EQ(p.frames.every_steps, 500);
  EXPECT_EQ(p.frames.log_steps_per_decade, 5.0);
  EXPECT_EQ(p.frames.log_steps_restart, 2500);
  EXPECT_EQ(parse({{"log_cycles", {{"per_decade", 4}}}}).frames.log_steps_restart, 0);
  EXPECT_EQ(input_error([] { parse({{"log_cycles", {{"per_decade", 0}}}}); }).json_path(), "frames.log_cycles.per_decade");
  EXPECT_EQ(input_error([] { parse({{"log_cycles", {{"per_decade", 5}, {"restart_every", 0}}}}); }).json_path(),
            "frames.log_cycles.restart_every");
  EXPECT_EQ(input_error([] { parse({{"log_cycles", {{"restart_every", 10}}}}); }).json_path(), "frames.log_cycles.per_decade");
}

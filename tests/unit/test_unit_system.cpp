// The run's unit system (tool/unit_system.hpp): read back from a run's parameters, and the symbolic
// units of the analysis stages expressed in it.
#include <gtest/gtest.h>

#include "anisodyn/tool/unit_system.hpp"

using anisodyn::tool::UnitSystem;
using anisodyn::tool::unit_system_of_run;

TEST(UnitSystem, ReducedWhenTheRunDeclaresNone) {
  for (const char* text : {R"({})", R"({"units": {"system": "reduced"}})", R"(null)"}) {
    const UnitSystem u = unit_system_of_run(nlohmann::json::parse(text));
    EXPECT_FALSE(u.si) << text;
    EXPECT_EQ(u.kT(), 1.0);
    EXPECT_EQ(u.express("length^2/tau"), "length^2/tau");
  }
}

TEST(UnitSystem, SiRunsSayMetresSecondsAndJoules) {
  const UnitSystem u = unit_system_of_run(nlohmann::json::parse(R"({"units": {"system": "SI", "length": 1e-6, "temperature": 300}})"));
  ASSERT_TRUE(u.si);
  EXPECT_DOUBLE_EQ(u.kT(), 1.380649e-23 * 300);
  EXPECT_EQ(u.express("length^2/tau"), "um^2/s");
  EXPECT_EQ(u.express("rad^2/tau"), "rad^2/s");
  EXPECT_EQ(u.express("tau"), "s");
  EXPECT_EQ(u.express("sigma"), "um");
  EXPECT_EQ(u.express("length^-d or rad^-3"), "um^-d or rad^-3");
  // words that merely contain the symbols are left alone
  EXPECT_EQ(u.express("lengths taut sigmas"), "lengths taut sigmas");
  EXPECT_EQ(u.to_json()["system"], "SI");
}

TEST(UnitSystem, UnnamedLengthUnitsAreWrittenInMetres) {
  UnitSystem u;
  u.si = true;
  u.length_m = 1.48e-8;
  EXPECT_EQ(u.express("length/tau"), "(1.48e-08 m)/s");
  u.length_m = 1e-9;
  EXPECT_EQ(u.express("length"), "nm");
}

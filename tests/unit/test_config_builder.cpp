// Configuration building: boxes for a packing fraction (any aspect ratio), lattice and random
// placement of mixtures without overlaps, tracer insertion into an existing state, the default
// alignment axis, and the clear failures when a target cannot be reached.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "anisodyn/config/builder.hpp"
#include "anisodyn/config/config_tool.hpp"
#include "anisodyn/interactions/hard_overlap.hpp"
#include "anisodyn/system/order.hpp"

using namespace anisodyn;

namespace {
Species board(double W) { return Species{"board", Shape::cuboid(1.0, W, 12.0), 1.0, {}, {}}; }
Species sphere(const char* name, double d) { return Species{name, Shape::sphere(d), 1.0, {}, {}}; }
}  // namespace

TEST(ConfigBuilder, BoxForPackingFractionHonoursAspectRatio) {
  const SpeciesTable sp = {board(3.4641), sphere("hs", 1.0)};
  const Vec3 L = box_edges_for_packing_fraction(sp, {100, 50}, 0.05, Vec3(1, 1, 3));
  EXPECT_NEAR(L.z() / L.x(), 3.0, 1e-12);
  EXPECT_NEAR(L.x(), L.y(), 1e-12);
  const double v = 100 * 3.4641 * 12.0 + 50 * M_PI / 6.0;
  EXPECT_NEAR(v / L.prod(), 0.05, 1e-12);
}

TEST(ConfigBuilder, DefaultAlignmentAxisFollowsProlateOrOblate) {
  EXPECT_EQ(default_alignment_axis(Shape::cuboid(1, 1, 12)), 2);       // rod-like: L
  EXPECT_EQ(default_alignment_axis(Shape::cuboid(1, 3.4641, 12)), 2);  // self-dual: L
  EXPECT_EQ(default_alignment_axis(Shape::cuboid(1, 8, 12)), 0);       // plate-like: T
  EXPECT_EQ(default_alignment_axis(Shape::spherocylinder(5, 1)), 2);
}

TEST(ConfigBuilder, AlignedLatticeOfAMixtureHasNoOverlapAndFullOrder) {
  State s;
  s.species = {board(8.0), sphere("tracer", 0.1)};
  s.box = Box(box_edges_for_packing_fraction(s.species, {400, 100}, 0.30, Vec3(1, 1, 3)));
  OrientationRule aligned;
  aligned.body_axis = default_alignment_axis(s.species[0].shape);
  Rng rng(1, 2);
  place_on_lattice(s, PlacementRequest{{400, 100}, {aligned, aligned}, 1000}, rng);
  ASSERT_EQ(s.particles.size(), 500u);
  EXPECT_NEAR(s.packing_fraction(), 0.30, 1e-12);
  EXPECT_FALSE(HardOverlap(s).first_overlap().has_value());
  const auto order = body_axis_order(s, 0);
  EXPECT_NEAR(order[0].order, 1.0, 1e-12);                  // T axes all along z
  EXPECT_NEAR(std::abs(order[0].director.z()), 1.0, 1e-12);
  for (std::size_t i = 0; i < s.particles.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(s.particles.position(i)[k], 0.0);
      EXPECT_LT(s.particles.position(i)[k], s.box.edges()[k]);
    }
}

TEST(ConfigBuilder, LatticeTooDenseFailsClearly) {
  State s;
  s.species = {board(3.4641)};
  s.box = Box(box_edges_for_packing_fraction(s.species, {500}, 0.05, Vec3::Ones()));
  Rng rng(1, 2);
  OrientationRule random{OrientationRule::Mode::Random};
  EXPECT_THROW(place_on_lattice(s, PlacementRequest{{500}, {random}, 1000}, rng), PlacementFailure);
}

TEST(ConfigBuilder, RandomInsertionOfTracersIntoAnExistingState) {
  State s;
  s.species = {board(1.0)};
  s.box = Box(Vec3(30, 30, 30));
  Rng rng(3, 4);
  OrientationRule random{OrientationRule::Mode::Random};
  insert_randomly(s, PlacementRequest{{150}, {random}, 10000}, rng);
  const std::vector<double> before_x = s.particles.x;
  s.species.push_back(sphere("tracer", 0.1));
  insert_randomly(s, PlacementRequest{{0, 200}, {random, OrientationRule{}}, 10000}, rng);
  ASSERT_EQ(s.particles.size(), 350u);
  for (std::size_t i = 0; i < 150; ++i) EXPECT_EQ(s.particles.x[i], before_x[i]);  // existing particles untouched
  std::set<std::int64_t> ids(s.particles.id.begin(), s.particles.id.end());
  EXPECT_EQ(ids.size(), 350u);  // new particles get fresh ids
  EXPECT_FALSE(HardOverlap(s).first_overlap().has_value());
}

TEST(ConfigBuilder, RandomInsertionBeyondReachFailsClearly) {
  State s;
  s.species = {sphere("hs", 1.0)};
  s.box = Box(box_edges_for_packing_fraction(s.species, {300}, 0.6, Vec3::Ones()));
  Rng rng(5, 6);
  try {
    insert_randomly(s, PlacementRequest{{300}, {OrientationRule{}}, 500}, rng);
    FAIL() << "random insertion at eta = 0.6 must fail";
  } catch (const PlacementFailure& e) {
    EXPECT_NE(std::string(e.what()).find("stuck"), std::string::npos) << e.what();
  }
}

TEST(ConfigTool, InsertionKeepsTheBoxAndRejectsAConflictingSpecies) {
  State existing;
  existing.species = {sphere("hs", 1.0)};
  existing.box = Box(Vec3(10, 10, 10));
  existing.particles.add(0, Vec3(5, 5, 5), Quat::Identity(), 0);
  nlohmann::json ok = {{"species", {{{"name", "tracer"}, {"shape", {{"type", "sphere"}, {"diameter", 0.2}}}}}},
                       {"composition", {{{"species", "tracer"}, {"count", 10}}}}};
  tool::ConfigNode cfg(ok, "insert.json");
  const State s = build_configuration(cfg, existing, 7);
  EXPECT_EQ(s.particles.size(), 11u);
  EXPECT_EQ(s.box.edges(), existing.box.edges());
  EXPECT_EQ(s.species.size(), 2u);

  nlohmann::json conflicting = ok;
  conflicting["species"][0]["name"] = "hs";  // same name, different diameter
  conflicting["composition"][0]["species"] = "hs";
  tool::ConfigNode bad(conflicting, "insert.json");
  EXPECT_THROW(build_configuration(bad, existing, 7), InputError);
}

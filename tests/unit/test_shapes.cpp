// The shape list (geometry/shape_list.hpp): every shape's JSON round trip, its queries against
// sampled geometry, and the H5MD species table storing shapes as JSON specs while still reading
// files that have only the fixed columns.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>

#include "anisodyn/core/quaternion.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/geometry/overlap.hpp"
#include "anisodyn/geometry/shapes.hpp"
#include "anisodyn/io/h5md.hpp"
#include "input_error.hpp"
#include "scratch_dir.hpp"

using namespace anisodyn;
using anisodyn::testing_support::input_error;

namespace {

const Shape kExamples[] = {Shape::sphere(1.3), Shape::cuboid(1.0, 3.4641, 12.0), Shape::spherocylinder(5.0, 1.0),
                           Shape::ellipsoid(Vec3(0.5, 1.0, 3.0))};

bool same(const Shape& a, const Shape& b) {
  return a.kind == b.kind && a.edges == b.edges && a.diameter == b.diameter && a.length == b.length;
}

Shape parse(const nlohmann::json& j) {
  tool::ConfigNode node(j, "species.json", "shape");
  Shape s = parse_shape(node);
  node.finish();
  return s;
}

/// Whether the body at the origin with rotation R contains lab point p, by the overlap test with a
/// vanishing sphere (contact counts).
bool contains(const Shape& s, const Mat3& R, const Vec3& p) {
  return overlap(s, R, Shape::sphere(1e-12), Mat3::Identity(), p);
}

}  // namespace

TEST(Shapes, EveryShapeOfTheListRoundTripsThroughItsJson) {
  static_assert(kShapeKindCount == 4);
  for (const Shape& s : kExamples) {
    const nlohmann::json j = s.spec();
    EXPECT_EQ(j.at("type"), shape_kind_name(s.kind));
    EXPECT_TRUE(same(parse(j), s)) << j.dump();
  }
  EXPECT_TRUE(same(parse({{"type", "cube"}, {"edge", 2.0}}), Shape::cuboid(2, 2, 2)));
  EXPECT_TRUE(same(parse({{"type", "ellipsoid"}, {"semi_axes", {1, 2, 3}}}), Shape::ellipsoid(Vec3(1, 2, 3))));
  const auto bad = input_error([] { parse({{"type", "ellipsoid"}, {"semi_axes", {1, -2, 3}}}); });
  EXPECT_EQ(bad.json_path(), "shape.semi_axes");
  EXPECT_EQ(input_error([] { parse({{"type", "torus"}}); }).json_path(), "shape.type");
}

TEST(Shapes, QueriesAgreeWithSampledGeometry) {
  // Volume by hit-or-miss sampling in the lab box of ±lab_half_extents (within 4 SE); the extents
  // and circumradius bound every sampled body point, and the extents are reached (within 5%: a cuboid reaches them only at a corner).
  Rng rng(7, 0);
  for (const Shape& s : kExamples) {
    const Mat3 R = uniform_quaternion(rng.uniform(), rng.uniform(), rng.uniform()).toRotationMatrix();
    const Vec3 h = s.lab_half_extents(R);
    const int n = 400000;
    int inside = 0;
    Vec3 reach = Vec3::Zero();
    double farthest = 0.0;
    for (int k = 0; k < n; ++k) {
      const Vec3 p(rng.uniform(-h.x(), h.x()), rng.uniform(-h.y(), h.y()), rng.uniform(-h.z(), h.z()));
      if (!contains(s, R, p)) continue;
      ++inside;
      reach = reach.cwiseMax(p.cwiseAbs());
      farthest = std::max(farthest, p.norm());
    }
    const double box = 8.0 * h.prod(), f = double(inside) / n;
    const double volume = box * f, se = box * std::sqrt(f * (1 - f) / n);
    EXPECT_NEAR(volume, s.volume(), 4 * se) << shape_kind_name(s.kind);
    EXPECT_LE(farthest, s.circumradius() * (1 + 1e-9)) << shape_kind_name(s.kind);
    for (int k = 0; k < 3; ++k) EXPECT_GT(reach[k], 0.95 * h[k]) << shape_kind_name(s.kind) << " axis " << k;
    // The inscribed sphere is inside; a point just beyond the circumradius along a body axis is not.
    EXPECT_TRUE(contains(s, R, 0.999 * s.inscribed_radius() * R.col(0))) << shape_kind_name(s.kind);
    EXPECT_FALSE(contains(s, R, 1.001 * s.circumradius() * R.col(2))) << shape_kind_name(s.kind);
  }
}

class ShapeStorage : public testing_support::ScratchDirTest {
 protected:
  ShapeStorage() : ScratchDirTest("shapes") {}
};

TEST_F(ShapeStorage, SpeciesShapesAreStoredAsJsonAndOldFilesStillRead) {
  State st;
  st.box = Box(Vec3(20, 20, 20));
  for (const Shape& s : kExamples) st.species.push_back(Species{shape_kind_name(s.kind), s, 1.0, Vec3::Ones(), Vec3::Ones()});
  for (int i = 0; i < 4; ++i) st.particles.add(i, Vec3(2 + 4 * i, 5, 5), Quat::Identity(), i);
  {
    io::H5mdWriter w(file("new.h5"), io::H5mdHeader{"anisodyn", "", "test", {}, {}, st.species});
    w.append_frame(st);
    w.commit();
  }
  const State back = io::H5mdReader(file("new.h5")).read_frame(-1);
  ASSERT_EQ(back.species.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_TRUE(same(back.species[k].shape, st.species[k].shape)) << k;

  // A file written before shape_spec: the kind name and the fixed columns are read.
  std::filesystem::copy_file(file("new.h5"), file("old.h5"));
  const hid_t f = H5Fopen(file("old.h5").c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_GE(H5Ldelete(f, "/parameters/species/shape_spec", H5P_DEFAULT), 0);
  H5Fclose(f);
  const State old = io::H5mdReader(file("old.h5")).read_frame(-1);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_TRUE(same(old.species[k].shape, st.species[k].shape)) << k;

  // With shape_spec, the fixed columns are not needed: another writer may leave them out.
  std::filesystem::copy_file(file("new.h5"), file("spec_only.h5"));
  const hid_t g = H5Fopen(file("spec_only.h5").c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(g, 0);
  for (const char* column : {"edges", "diameter", "length"})
    EXPECT_GE(H5Ldelete(g, (std::string("/parameters/species/") + column).c_str(), H5P_DEFAULT), 0) << column;
  H5Fclose(g);
  const State spec_only = io::H5mdReader(file("spec_only.h5")).read_frame(-1);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_TRUE(same(spec_only.species[k].shape, st.species[k].shape)) << k;
}

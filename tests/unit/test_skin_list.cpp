// Skin lists (neighbors/skin_list.hpp): the two geometric facts they rest on, checked against
// exact point–body distances, and HardOverlap with lists against HardOverlap without them and an
// O(N²) brute-force search along a random walk of accepted moves.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "anisodyn/config/builder.hpp"
#include "anisodyn/core/quaternion.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/geometry/overlap.hpp"
#include "anisodyn/interactions/hard_overlap.hpp"
#include "brute_force_search.hpp"
#include "reference_ellipsoid.hpp"

using namespace anisodyn;
using anisodyn::testing_support::brute_force_overlaps;

namespace {

Quat random_quaternion(Rng& rng) { return uniform_quaternion(rng.uniform(), rng.uniform(), rng.uniform()); }

Vec3 random_in_ball(Rng& rng, double radius) {
  while (true) {
    const Vec3 v(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
    if (v.squaredNorm() <= 1.0) return radius * v;
  }
}

Vec3 random_unit(Rng& rng) {
  while (true) {
    const Vec3 v = random_in_ball(rng, 1.0);
    if (v.norm() > 1e-3) return v.normalized();
  }
}

/// A point of the body in its own frame: corners and face points of cuboids, points of
/// spherocylinder caps and rims, anything in a sphere; interior points too.
Vec3 random_body_point(const Shape& shape, Rng& rng) {
  switch (shape.kind) {
    case ShapeKind::Cuboid: {
      const Vec3 h = shape.half_extents();
      Vec3 c;
      for (int k = 0; k < 3; ++k) {
        const double u = rng.uniform();
        c[k] = u < 0.3 ? -h[k] : (u < 0.6 ? h[k] : rng.uniform(-h[k], h[k]));
      }
      return c;
    }
    case ShapeKind::Spherocylinder: {
      const double s = rng.uniform() < 0.5 ? (rng.uniform() < 0.5 ? -0.5 : 0.5) * shape.length
                                           : rng.uniform(-0.5, 0.5) * shape.length;
      return Vec3(0, 0, s) + (rng.uniform() < 0.5 ? 0.5 * shape.diameter * random_unit(rng) : random_in_ball(rng, 0.5 * shape.diameter));
    }
    case ShapeKind::Ellipsoid: {
      // The unit ball (surface or inside) stretched by the semi-axes.
      const Vec3 u = rng.uniform() < 0.5 ? random_unit(rng) : random_in_ball(rng, 1.0);
      return u.cwiseProduct(shape.half_extents());
    }
    case ShapeKind::Sphere: break;
  }
  return rng.uniform() < 0.5 ? 0.5 * shape.diameter * random_unit(rng) : random_in_ball(rng, 0.5 * shape.diameter);
}

/// Exact distance from lab point p to the body at the origin with rotation R (0 inside).
double distance_to_body(const Shape& shape, const Mat3& R, const Vec3& p) {
  const Vec3 c = R.transpose() * p;
  switch (shape.kind) {
    case ShapeKind::Cuboid: return (c.cwiseAbs() - shape.half_extents()).cwiseMax(0.0).norm();
    case ShapeKind::Spherocylinder: {
      const double s = std::clamp(c.z(), -0.5 * shape.length, 0.5 * shape.length);
      return std::max((c - Vec3(0, 0, s)).norm() - 0.5 * shape.diameter, 0.0);
    }
    case ShapeKind::Ellipsoid:  // the long-double reference of the ellipsoid overlap tests
      return static_cast<double>(reference::ellipsoid_point_distance(reference::ld(shape.half_extents()),
                                                                     reference::ld(Mat3(Mat3::Identity())), reference::ld(c)));
    case ShapeKind::Sphere: break;
  }
  return std::max(c.norm() - 0.5 * shape.diameter, 0.0);
}

const Shape kShapes[] = {Shape::cuboid(1.0, 3.4641, 12.0), Shape::cuboid(1.0, 1.0, 12.0), Shape::spherocylinder(10.0, 1.0),
                         Shape::sphere(0.7), Shape::ellipsoid(Vec3(0.5, 1.5, 4.0))};

/// Whether lab point p lies in the body at the origin with rotation R (contact counts).
bool contains(const Shape& shape, const Mat3& R, const Vec3& p) {
  if (shape.kind == ShapeKind::Ellipsoid)  // exact, without the overlap kernel
    return (R.transpose() * p).cwiseQuotient(shape.half_extents()).squaredNorm() <= 1.0;
  return overlap(shape, R, Shape::sphere(0.0), Mat3::Identity(), p);
}

}  // namespace

TEST(SkinGeometry, MotionBoundCoversEveryPointOfTheMovedBody) {
  Rng rng(41, 0);
  for (const Shape& shape : kShapes) {
    double worst_ratio = 0.0;  // largest distance seen / bound
    for (int move = 0; move < 2000; ++move) {
      const Mat3 from = random_quaternion(rng).toRotationMatrix();
      // Small DMC-like moves and large ones.
      const double size = move % 2 ? 0.05 : 1.0;
      const Vec3 dr = random_in_ball(rng, size);
      const Mat3 to = (Quat(from) * quat_from_rotation_vector(random_in_ball(rng, size))).normalized().toRotationMatrix();
      const double bound = motion_bound(shape, dr, from, to);
      for (int k = 0; k < 40; ++k) {
        const double d = distance_to_body(shape, from, dr + to * random_body_point(shape, rng));
        ASSERT_LE(d, bound * (1.0 + 1e-12) + 1e-14) << shape_kind_name(shape.kind) << " move " << move;
        worst_ratio = std::max(worst_ratio, d / bound);
      }
    }
    // The bound is not loose by orders of magnitude (it is exact for a pure translation).
    EXPECT_GT(worst_ratio, 0.5) << shape_kind_name(shape.kind);
  }
}

TEST(SkinGeometry, PureTranslationBoundIsTheDistance) {
  const Shape board = Shape::cuboid(1.0, 3.4641, 12.0);
  const Mat3 R = Quat(0.3, 0.1, -0.7, 0.2).normalized().toRotationMatrix();
  const Vec3 dr = 0.2 * R.col(1);  // along a body axis: the leading face moves off by exactly |dr|
  EXPECT_DOUBLE_EQ(motion_bound(board, dr, R, R), 0.2);
  EXPECT_NEAR(distance_to_body(board, R, dr + R * board.half_extents()), 0.2, 1e-12);
}

TEST(SkinGeometry, GrownBodyHoldsEveryPointWithinTheSkin) {
  Rng rng(43, 0);
  const double t = 0.3;
  for (const Shape& shape : kShapes) {
    const Shape grown = shape.grown(t);
    for (int k = 0; k < 20000; ++k) {
      const Mat3 R = random_quaternion(rng).toRotationMatrix();
      const Vec3 p = R * random_body_point(shape, rng) + 0.999 * t * random_unit(rng);
      ASSERT_LE(distance_to_body(shape, R, p), t * (1.0 + 1e-12));
      ASSERT_TRUE(contains(grown, R, p)) << shape_kind_name(shape.kind) << " sample " << k;
    }
    // Grown by t, not more: points just beyond t off a face (or the cap) are outside; for the
    // ellipsoid (scaled by 1 + t/a_min, conservative along the longer axes) off the shortest axis.
    const Vec3 off_face = shape.kind == ShapeKind::Cuboid      ? Vec3(0, 0, 0.5 * shape.edges.z() + 1.001 * t)
                          : shape.kind == ShapeKind::Ellipsoid ? Vec3(0.5 * shape.edges.x() + 1.001 * t, 0, 0)
                                                               : Vec3(0, 0, shape.circumradius() + 1.001 * t);
    EXPECT_FALSE(contains(grown, Mat3::Identity(), off_face)) << shape_kind_name(shape.kind);
  }
}

namespace {

/// Boards 12×1×1 with spheres d = 0.5 among them, dense enough that small moves often collide.
State board_sphere_mixture(Rng& rng) {
  State s;
  s.species.push_back(Species{"board", Shape::cuboid(1.0, 1.0, 12.0), 1.0, {}, {}});
  s.species.push_back(Species{"hs", Shape::sphere(0.5), 1.0, {}, {}});
  s.box = Box(Vec3(26, 26, 30));
  PlacementRequest req{{260, 300}, {OrientationRule{OrientationRule::Mode::Random}, OrientationRule{}}, 200000};
  insert_randomly(s, req, rng);
  return s;
}

/// The lists' defining property, checked over all pairs: i and j are on each other's lists
/// exactly when their reference placements, grown by the half-skins, overlap (sphere–sphere
/// pairs are never listed).
void expect_lists_match_references(const State& s, const SkinList& lists) {
  const std::size_t n = s.particles.size();
  int listed_pairs = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const int a = s.particles.species[i];
    const auto& ni = lists.neighbors(static_cast<std::int32_t>(i));
    for (std::size_t j = i + 1; j < n; ++j) {
      const int b = s.particles.species[j];
      const bool on_list = std::find(ni.begin(), ni.end(), static_cast<std::int32_t>(j)) != ni.end();
      const auto& nj = lists.neighbors(static_cast<std::int32_t>(j));
      ASSERT_EQ(on_list, std::find(nj.begin(), nj.end(), static_cast<std::int32_t>(i)) != nj.end()) << i << " " << j;
      bool expected = false;
      if (lists.pair_listed(a, b)) {
        const auto ii = static_cast<std::int32_t>(i), jj = static_cast<std::int32_t>(j);
        expected = overlap(s.species[static_cast<std::size_t>(a)].shape.grown(lists.half_skin(a)), lists.reference_rotation(ii),
                           s.species[static_cast<std::size_t>(b)].shape.grown(lists.half_skin(b)), lists.reference_rotation(jj),
                           s.box.min_image(lists.reference_position(jj) - lists.reference_position(ii)));
      }
      ASSERT_EQ(on_list, expected) << "pair " << i << " " << j;
      listed_pairs += on_list;
    }
  }
  EXPECT_GT(listed_pairs, static_cast<int>(n));
}

}  // namespace

// A random walk of DMC-like moves (and every seventh a large one, which leaves the skin) with the
// accepted moves applied: every trial must get the same answer with lists, without them, and
// from the brute-force search.
TEST(SkinList, HardOverlapWithListsDecidesAsWithoutAndAsBruteForce) {
  Rng rng(47, 0);
  State s = board_sphere_mixture(rng);
  HardOverlap plain(s), listed(s);
  listed.use_skin_lists({0.25, 0.3});
  ASSERT_FALSE(listed.first_overlap().has_value());
  const std::int64_t resets_at_build = listed.skin_lists().references_reset();
  int overlapping = 0, accepted = 0, outside_skin = 0;
  const int trials = 30000;
  for (int t = 0; t < trials; ++t) {
    if (t % 10000 == 0) expect_lists_match_references(s, listed.skin_lists());
    const std::size_t i = rng.index(s.particles.size());
    const auto ii = static_cast<std::int32_t>(i);
    const double step = t % 7 == 0 ? 1.0 : 0.08;
    Vec3 r = s.particles.position(i) + Vec3(rng.uniform(-step, step), rng.uniform(-step, step), rng.uniform(-step, step));
    Int3 image = s.particles.image(i);
    s.box.wrap(r, image);
    const Quat q = s.particles.species[i] == 0
                       ? rotate_in_body_frame(s.particles.orientation(i), Vec3(rng.uniform(-step, step), rng.uniform(-step, step), rng.uniform(-step, step)) * 0.2)
                       : s.particles.orientation(i);
    const Mat3 rot = q.toRotationMatrix();
    const bool expected = brute_force_overlaps(s, i, r, rot);
    ASSERT_EQ(plain.overlaps(ii, r, rot), expected) << "trial " << t;
    ASSERT_EQ(listed.overlaps(ii, r, rot), expected) << "trial " << t;
    if (t % 50 == 0) {
      ASSERT_EQ(listed.count_overlaps(ii, r, rot), plain.count_overlaps(ii, r, rot)) << "trial " << t;
    }
    if (expected) { ++overlapping; continue; }
    const int species = s.particles.species[i];
    outside_skin += !listed.skin_lists().within_skin(ii, s.species[static_cast<std::size_t>(species)].shape, species, s.box, r, rot);
    s.particles.set_position(i, r);
    s.particles.set_image(i, image);
    s.particles.set_orientation(i, q);
    plain.moved(ii, r, rot);
    listed.moved(ii, r, rot);
    ++accepted;
  }
  EXPECT_GT(overlapping, trials / 20);
  EXPECT_GT(accepted, trials / 2);
  // Bodies left their skins and were re-referenced, so the incremental path was exercised.
  EXPECT_GT(outside_skin, 500);
  EXPECT_EQ(listed.skin_lists().references_reset() - resets_at_build, outside_skin);
  EXPECT_FALSE(listed.first_overlap().has_value());
  expect_lists_match_references(s, listed.skin_lists());
}

// Sphere–sphere pairs stay on the cell grid; a species in no listed pair keeps no references.
TEST(SkinList, SpheresAloneAreNotListed) {
  Rng rng(53, 0);
  State s;
  s.species.push_back(Species{"hs", Shape::sphere(1.0), 1.0, {}, {}});
  s.box = Box(Vec3(12, 12, 12));
  insert_randomly(s, PlacementRequest{{400}, {OrientationRule{}}, 100000}, rng);
  HardOverlap ho(s);
  ho.use_skin_lists({0.2});
  EXPECT_FALSE(ho.skin_lists().any());
  EXPECT_FALSE(ho.skin_lists().has_reference(0));
}

// Bodies inserted one by one (configuration building) join the lists of those already there.
TEST(SkinList, InsertedBodiesAreListed) {
  Rng rng(59, 0);
  const State full = board_sphere_mixture(rng);
  State s;
  s.species = full.species;
  s.box = full.box;
  const std::size_t half = full.particles.size() / 2;
  auto append = [&](std::size_t j) {
    s.particles.add(full.particles.species[j], full.particles.position(j), full.particles.orientation(j), full.particles.id[j]);
  };
  for (std::size_t j = 0; j < half; ++j) append(j);
  std::vector<std::size_t> still_to_come(full.species.size(), 0);
  for (std::size_t j = half; j < full.particles.size(); ++j) ++still_to_come[static_cast<std::size_t>(full.particles.species[j])];
  HardOverlap ho(s, still_to_come);
  ho.use_skin_lists({0.25, 0.3});
  for (std::size_t j = half; j < full.particles.size(); ++j) {
    append(j);
    ho.inserted(static_cast<std::int32_t>(j));
  }
  expect_lists_match_references(s, ho.skin_lists());
  int overlapping = 0;
  for (int t = 0; t < 4000; ++t) {
    const std::size_t i = rng.index(s.particles.size());
    Vec3 r = s.particles.position(i) + random_in_ball(rng, 0.1);
    Int3 image(0, 0, 0);
    s.box.wrap(r, image);
    const Mat3 rot = rotate_in_body_frame(s.particles.orientation(i), random_in_ball(rng, 0.02)).toRotationMatrix();
    const bool expected = brute_force_overlaps(s, i, r, rot);
    overlapping += expected;
    ASSERT_EQ(ho.overlaps(static_cast<std::int32_t>(i), r, rot), expected) << "trial " << t;
  }
  EXPECT_GT(overlapping, 100);
}

// Overlap kernels on hand-built configurations: exact contact (counts as overlap; coordinates
// exactly representable), just separated, parallel faces and edges, edge–edge crossings,
// (near-)identical orientations, coincident centres, nested bodies, the negative projections that
// OCSI's absolute value is for, and the generic dispatcher in both argument orders. Each case is
// also checked against the long-double reference of tests/support/reference_overlap.hpp.
#include <gtest/gtest.h>

#include <cmath>
#include <source_location>
#include <stdexcept>

#include "anisodyn/core/quaternion.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/geometry/cuboid_cuboid.hpp"
#include "anisodyn/geometry/cuboid_sphere.hpp"
#include "anisodyn/geometry/overlap.hpp"
#include "anisodyn/geometry/sphere_sphere.hpp"
#include "anisodyn/geometry/spherocylinder.hpp"
#include "reference_overlap.hpp"

using namespace anisodyn;
namespace ref = anisodyn::reference;

namespace {

const Mat3 I3 = Mat3::Identity();
const double kSqrt12 = 3.4641016151377544;  // board width W* = √12 (T = 1, L = 12)

double up(double x) { return std::nextafter(x, HUGE_VAL); }

Mat3 rot(const Vec3& axis, double angle) { return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(); }

Mat3 random_rot(Rng& rng) {
  const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
  return uniform_quaternion(u1, u2, u3).toRotationMatrix();
}

/// Checks the dispatcher in both argument orders against `expected`, and the reference: with its
/// default band it must agree or call the pair indeterminate; with a zero band (exact contact
/// counts as overlap) it must agree whenever `exact_ref` is set.
void expect_pair(const Shape& a, const Mat3& Ra, const Shape& b, const Mat3& Rb, const Vec3& t, bool expected,
                 bool exact_ref = true, std::source_location loc = std::source_location::current()) {
  ::testing::ScopedTrace trace(loc.file_name(), static_cast<int>(loc.line()),
                               ::testing::Message() << "t = (" << t.transpose() << ")");
  EXPECT_EQ(overlap(a, Ra, b, Rb, t), expected) << "a,b order";
  EXPECT_EQ(overlap(b, Rb, a, Ra, Vec3(-t)), expected) << "b,a order";
  const ref::Verdict v = ref::overlap_verdict(a, Ra, b, Rb, t);
  if (v != ref::Verdict::Indeterminate) {
    EXPECT_EQ(v == ref::Verdict::Overlap, expected) << "reference";
  }
  if (exact_ref) {
    EXPECT_EQ(ref::overlap_verdict(a, Ra, b, Rb, t, 0.0) == ref::Verdict::Overlap, expected) << "reference, no band";
  }
}

}  // namespace

// ---- sphere–sphere -------------------------------------------------------------------------------

TEST(SphereSphere, ContactCountsAsOverlap) {
  EXPECT_TRUE(overlap_sphere_sphere(0.5, 0.5, Vec3(1, 0, 0)));
  EXPECT_TRUE(overlap_sphere_sphere(1.5, 0.5, Vec3(0, 0, -2)));
  EXPECT_TRUE(overlap_sphere_sphere(0.25, 0.5, Vec3(0.75 * 0.6, 0.75 * 0.8, 0)));  // not exact in binary …
  EXPECT_TRUE(overlap_sphere_sphere(0.5, 2.0, Vec3(1.5, 2.0, 0)));                 // |t| = 2.5 exactly
  EXPECT_FALSE(overlap_sphere_sphere(0.5, 0.5, Vec3(up(1.0), 0, 0)));
  EXPECT_FALSE(overlap_sphere_sphere(0.5, 2.0, Vec3(1.5, up(2.0), 0)));
}

TEST(SphereSphere, CoincidentCentresAndFloat) {
  EXPECT_TRUE(overlap_sphere_sphere(0.05, 0.05, Vec3::Zero()));
  EXPECT_TRUE(overlap_sphere_sphere<float>(0.5f, 2.0f, 1.5f, 2.0f, 0.0f));
  EXPECT_FALSE(overlap_sphere_sphere<float>(0.5f, 2.0f, 1.5f, std::nextafter(2.0f, 3.0f), 0.0f));
  const Shape s1 = Shape::sphere(1.0), s3 = Shape::sphere(3.0);
  expect_pair(s1, I3, s3, I3, Vec3(2, 0, 0), true);
  expect_pair(s1, I3, s3, I3, Vec3(up(2.0), 0, 0), false);
}

// ---- cuboid–sphere (OCSI) ------------------------------------------------------------------------

TEST(CuboidSphere, FaceEdgeAndCornerContact) {
  const Vec3 half(0.5, 1.5, 6.0);
  // Face contact on every face, both signs: the distance along the axis equals c_k + R.
  for (int k = 0; k < 3; ++k)
    for (double sgn : {-1.0, 1.0}) {
      Vec3 r = Vec3::Zero();
      r[k] = sgn * (half[k] + 0.5);
      EXPECT_TRUE(overlap_cuboid_sphere(I3, half, r, 0.5)) << k << " " << sgn;
      EXPECT_EQ(cuboid_sphere_dmin2(I3, half, r), 0.25);
      r[k] = sgn * up(half[k] + 0.5);
      EXPECT_FALSE(overlap_cuboid_sphere(I3, half, r, 0.5)) << k << " " << sgn;
    }
  // Edge contact: 3-4-5 triangle off the edge (x, y) = (0.5, 1.5), sphere radius 1.25.
  EXPECT_TRUE(overlap_cuboid_sphere(I3, half, Vec3(0.5 + 0.75, -1.5 - 1.0, 2.0), 1.25));
  EXPECT_FALSE(overlap_cuboid_sphere(I3, half, Vec3(0.5 + 0.75, -1.5 - 1.0, 2.0), std::nextafter(1.25, 0.0)));
  // Corner contact: offsets (−1, 2, 2) from the corner (−0.5, 1.5, 6), distance 3.
  EXPECT_EQ(cuboid_sphere_dmin2(I3, half, Vec3(-1.5, 3.5, 8.0)), 9.0);
  EXPECT_TRUE(overlap_cuboid_sphere(I3, half, Vec3(-1.5, 3.5, 8.0), 3.0));
  EXPECT_FALSE(overlap_cuboid_sphere(I3, half, Vec3(-1.5, 3.5, up(8.0)), 3.0));
}

TEST(CuboidSphere, NegativeProjectionsNeedTheAbsoluteValue) {
  // Without |·| a sphere far out on the negative side of any axis would look "inside" on that axis.
  const Vec3 half(0.5, 1.5, 6.0);
  EXPECT_FALSE(overlap_cuboid_sphere(I3, half, Vec3(-3.0, 0, 0), 0.5));
  EXPECT_FALSE(overlap_cuboid_sphere(I3, half, Vec3(0, -4.0, 0), 0.5));
  EXPECT_FALSE(overlap_cuboid_sphere(I3, half, Vec3(-1.0, -2.0, -7.0), 0.5));
  EXPECT_DOUBLE_EQ(cuboid_sphere_dmin2(I3, half, Vec3(-3.0, 0, 0)), 6.25);
  EXPECT_DOUBLE_EQ(cuboid_sphere_dmin2(I3, half, Vec3(-1.0, -2.0, -7.0)), 0.25 + 0.25 + 1.0);
  // A rotation with negative entries (90° about z: ê_T = ŷ, ê_W = −x̂): a lab point on +x has a
  // negative projection on ê_W.
  Mat3 R;
  R << 0, -1, 0,  //
      1, 0, 0,    //
      0, 0, 1;
  EXPECT_FALSE(overlap_cuboid_sphere(R, half, Vec3(3.0, 0, 0), 1.0));   // 3 − 1.5 = 1.5 > 1
  EXPECT_TRUE(overlap_cuboid_sphere(R, half, Vec3(2.5, 0, 0), 1.0));    // exact contact
  EXPECT_DOUBLE_EQ(cuboid_sphere_dmin2(R, half, Vec3(3.0, 0, 0)), 2.25);
  EXPECT_FALSE(overlap_cuboid_sphere(R, half, Vec3(0, -2.0, 0), 1.0));  // projection on ê_T = −2
  expect_pair(Shape::cuboid(1, 3, 12), R, Shape::sphere(2.0), I3, Vec3(2.5, 0, 0), true);
  expect_pair(Shape::cuboid(1, 3, 12), R, Shape::sphere(2.0), I3, Vec3(-up(2.5), 0, 0), false);
}

TEST(CuboidSphere, NestedAndCoincident) {
  const Vec3 half(0.5, 4.0, 6.0);
  EXPECT_TRUE(overlap_cuboid_sphere(I3, half, Vec3(0.1, -2.0, 3.0), 0.05));
  EXPECT_EQ(cuboid_sphere_dmin2(I3, half, Vec3(0.1, -2.0, 3.0)), 0.0);
  EXPECT_TRUE(overlap_cuboid_sphere(I3, half, Vec3::Zero(), 0.05));
  Rng rng(7, 0);
  const Mat3 R = random_rot(rng);
  expect_pair(Shape::cuboid(1, 8, 12), R, Shape::sphere(0.1), I3, R * Vec3(0.1, -2.0, 3.0), true);
  expect_pair(Shape::sphere(3.0), I3, Shape::cuboid(1, 1, 1), R, Vec3::Zero(), true);
}

TEST(CuboidSphere, FloatMatchesDoubleOnRepresentableCases) {
  const float axes[9] = {0, 1, 0, -1, 0, 0, 0, 0, 1};  // columns ê_T = ŷ, ê_W = −x̂, ê_L = ẑ
  const float half[3] = {0.5f, 1.5f, 6.0f};
  const float p1[3] = {2.5f, 0, 0}, p2[3] = {3.0f, 0, 0}, p3[3] = {-1.0f, -0.5f, 5.0f};
  EXPECT_TRUE(overlap_cuboid_sphere<float>(axes, half, p1, 1.0f));
  EXPECT_FALSE(overlap_cuboid_sphere<float>(axes, half, p2, 1.0f));
  EXPECT_EQ(cuboid_sphere_dmin2<float>(axes, half, p2), 2.25f);
  EXPECT_EQ(cuboid_sphere_dmin2<float>(axes, half, p3), 0.0f);
  const Eigen::Matrix3f Rf = Eigen::Map<const Eigen::Matrix3f>(axes);
  EXPECT_EQ(cuboid_sphere_dmin2(Rf, Eigen::Vector3f(half), Eigen::Vector3f(p2)), 2.25f);
}

TEST(CuboidSphere, DminMatchesReferenceOnRandomPoints) {
  Rng rng(11, 0);
  for (int n = 0; n < 20000; ++n) {
    const Mat3 R = random_rot(rng);
    const Vec3 half(rng.uniform(0.05, 6), rng.uniform(0.05, 6), rng.uniform(0.05, 6));
    const Vec3 p(rng.uniform(-12, 12), rng.uniform(-12, 12), rng.uniform(-12, 12));
    const double expected = double(ref::cuboid_point_dist2(ref::ld(half), ref::ld(R), ref::ld(p)));
    EXPECT_NEAR(cuboid_sphere_dmin2(R, half, p), expected, 1e-13 * (1 + expected));
  }
}

// ---- cuboid–cuboid (SAT) -------------------------------------------------------------------------

TEST(CuboidCuboid, ParallelFacesInContact) {
  const Shape cube = Shape::cuboid(1, 1, 1), board = Shape::cuboid(1, kSqrt12, 12);
  expect_pair(cube, I3, cube, I3, Vec3(1, 0, 0), true);
  expect_pair(cube, I3, cube, I3, Vec3(0.25, -1, 0.75), true);  // offset faces still in contact
  expect_pair(cube, I3, cube, I3, Vec3(0, 0, -1 - 1e-9), false);
  expect_pair(board, I3, board, I3, Vec3(1, 0, 0), true);
  expect_pair(board, I3, board, I3, Vec3(0, kSqrt12, 5), true);
  expect_pair(board, I3, board, I3, Vec3(0, -kSqrt12 - 1e-9, 5), false);
  expect_pair(board, I3, board, I3, Vec3(0.5, 1, 12), true);  // end faces
  expect_pair(board, I3, board, I3, Vec3(0.5, 1, 12 + 1e-9), false);
  // A cube face on a board face, the cube turned by 30° about the common normal.
  expect_pair(board, I3, cube, rot(Vec3(1, 0, 0), M_PI / 6), Vec3(1, 0.3, -2), true, false);
  expect_pair(board, I3, cube, rot(Vec3(1, 0, 0), M_PI / 6), Vec3(1 + 1e-9, 0.3, -2), false);
}

TEST(CuboidCuboid, ParallelEdgesInContact) {
  const Shape board = Shape::cuboid(1, kSqrt12, 12);
  expect_pair(board, I3, board, I3, Vec3(1, kSqrt12, 3), true);  // T–W edges touch along L
  expect_pair(board, I3, board, I3, Vec3(1 + 1e-9, kSqrt12, 3), false);
  expect_pair(board, I3, board, I3, Vec3(1, kSqrt12 + 1e-9, 3), false);
  expect_pair(board, I3, board, I3, Vec3(-1, -kSqrt12, -12), true);  // corner to corner
  expect_pair(board, I3, board, I3, Vec3(-1, -kSqrt12, -12 - 1e-9), false);
}

TEST(CuboidCuboid, EdgeEdgeCrossing) {
  // A turned 45° about x (top ridge along x at height √2/2); B turned 45° about y (bottom ridge
  // along y at −√2/2). The ridges cross above the origin; contact at height √2. Only the edge–edge
  // axis A_x × B_y separates when B is lifted.
  const Shape cube = Shape::cuboid(1, 1, 1);
  const Mat3 Ra = rot(Vec3(1, 0, 0), M_PI / 4), Rb = rot(Vec3(0, 1, 0), M_PI / 4);
  for (double rel : {1e-9, 1e-6, 1e-3}) {
    expect_pair(cube, Ra, cube, Rb, Vec3(0, 0, std::sqrt(2.0) * (1 - rel)), true, false);
    expect_pair(cube, Ra, cube, Rb, Vec3(0, 0, std::sqrt(2.0) * (1 + rel)), false, false);
  }
  // Interpenetrating ridges: no vertex of either cube is inside the other.
  expect_pair(cube, Ra, cube, Rb, Vec3(0, 0, 1.3), true);
  // Boards crossing like a plus sign, centred together: no vertex inside the other board either.
  const Shape rod = Shape::cuboid(1, 1, 12);
  expect_pair(rod, I3, rod, rot(Vec3(1, 0, 0), M_PI / 2), Vec3::Zero(), true, false);
  expect_pair(rod, I3, rod, rot(Vec3(1, 0, 0), M_PI / 2), Vec3(1 + 1e-9, 0, 0), false, false);
}

TEST(CuboidCuboid, IdenticalAndNearParallelOrientations) {
  Rng rng(3, 0);
  const Shape cube = Shape::cuboid(1, 1, 1), board = Shape::cuboid(1, kSqrt12, 12);
  for (int n = 0; n < 200; ++n) {
    const Mat3 R = random_rot(rng);
    for (double angle : {0.0, 1e-12, 1e-10}) {
      const Vec3 axis(rng.normal(), rng.normal(), rng.normal());
      const Mat3 Rb = angle == 0.0 ? R : Mat3(R * rot(axis, angle));
      // Displaced along a body axis by the contact distance (1 ± 1e-8): faces parallel.
      for (int k = 0; k < 3; ++k) {
        expect_pair(cube, R, cube, Rb, (1 - 1e-8) * R.col(k), true, false);
        expect_pair(cube, R, cube, Rb, (1 + 1e-8) * R.col(k), false, false);
        const double s = board.edges[k];
        expect_pair(board, R, board, Rb, s * (1 - 1e-8) * R.col(k), true, false);
        expect_pair(board, R, board, Rb, s * (1 + 1e-8) * R.col(k), false, false);
      }
      // Parallel edges: displaced along the T–W diagonal.
      const Vec3 d = R.col(0) + kSqrt12 * R.col(1);
      expect_pair(board, R, board, Rb, (1 - 1e-8) * d, true, false);
      expect_pair(board, R, board, Rb, (1 + 1e-8) * d, false, false);
    }
  }
}

TEST(CuboidCuboid, CoincidentCentresAndNested) {
  Rng rng(5, 0);
  const Shape board = Shape::cuboid(1, 8, 12), small = Shape::cuboid(0.1, 0.1, 0.1);
  for (int n = 0; n < 100; ++n) {
    const Mat3 Ra = random_rot(rng), Rb = random_rot(rng);
    expect_pair(board, Ra, board, Rb, Vec3::Zero(), true);
    // Small cube deep inside the big one, anywhere within 0.3 of its T faces.
    const Vec3 body(rng.uniform(-0.3, 0.3), rng.uniform(-3.5, 3.5), rng.uniform(-5.5, 5.5));
    expect_pair(board, Ra, small, Rb, Ra * body, true);
    expect_pair(small, Rb, board, Ra, -(Ra * body), true);
  }
}

TEST(CuboidCuboid, MatchesReferenceOnCrossedBoards) {
  // Boards at right angles sliding past each other: many exactly representable contacts.
  const Shape board = Shape::cuboid(1, kSqrt12, 12);
  const Mat3 Rb = rot(Vec3(1, 0, 0), M_PI / 2);  // B's L axis along −y … exact up to rounding of cos
  for (double z = -8; z <= 8; z += 0.5)
    for (double x : {0.0, 0.5, 0.999, 1.001, 1.5}) {
      const Vec3 t(x, 0, z);
      const ref::Verdict v = ref::overlap_verdict(board, I3, board, Rb, t);
      if (v == ref::Verdict::Indeterminate) continue;
      EXPECT_EQ(overlap(board, I3, board, Rb, t), v == ref::Verdict::Overlap) << x << " " << z;
    }
}

// ---- spherocylinders -----------------------------------------------------------------------------

TEST(Spherocylinder, ParallelAndCollinear) {
  const Shape rod = Shape::spherocylinder(10, 1);  // h = 5, radius 0.5
  Mat3 flip = Mat3::Identity();
  flip(1, 1) = flip(2, 2) = -1;  // axis −z: anti-parallel
  for (const Mat3& Rb : {I3, flip}) {
    expect_pair(rod, I3, rod, Rb, Vec3(1, 0, 0), true);       // side by side
    expect_pair(rod, I3, rod, Rb, Vec3(up(1.0), 0, 0), false);
    expect_pair(rod, I3, rod, Rb, Vec3(0, 1, 3), true);
    expect_pair(rod, I3, rod, Rb, Vec3(0, up(1.0), -3), false);
    expect_pair(rod, I3, rod, Rb, Vec3(0, 0, 11), true);      // end to end
    expect_pair(rod, I3, rod, Rb, Vec3(0, 0, up(11.0)), false);
    expect_pair(rod, I3, rod, Rb, Vec3(0, 0, 0), true);       // coincident
    expect_pair(rod, I3, rod, Rb, Vec3(0.75, 0, 10.5), true); // caps: |(0.75, 0.5)| < 1 … overlap
  }
  // Cap to cap, exact 3-4-5 contact: caps (0, 0, 5) and (1.5, 0, 7), radii 1.25 + 1.25.
  const Shape fat = Shape::spherocylinder(10, 2.5);
  expect_pair(fat, I3, fat, I3, Vec3(1.5, 0, 12), true);
  expect_pair(fat, I3, fat, I3, Vec3(1.5, 0, up(12.0)), false);
}

TEST(Spherocylinder, NearParallel) {
  const Shape rod = Shape::spherocylinder(19, 1);
  Rng rng(9, 0);
  for (int n = 0; n < 200; ++n) {
    const Mat3 R = random_rot(rng);
    for (double angle : {1e-14, 1e-12, 1e-10, 1e-8}) {
      const Mat3 Rb = R * rot(Vec3(rng.normal(), rng.normal(), 0), angle);  // tilt off the axis
      const Vec3 side = R.col(0), along = R.col(2);
      for (double shift : {0.0, 3.0, 18.0}) {
        expect_pair(rod, R, rod, Rb, (1 - 1e-7) * side + shift * along, true, false);
        expect_pair(rod, R, rod, Rb, (1 + 1e-7) * side + shift * along, false, false);
      }
      expect_pair(rod, R, rod, Rb, (20 - 1e-7) * along, true, false);
      expect_pair(rod, R, rod, Rb, (20 + 1e-7) * along, false, false);
    }
  }
}

TEST(Spherocylinder, CrossedAndEndpoints) {
  const Shape rod = Shape::spherocylinder(10, 1), fat = Shape::spherocylinder(10, 5);
  const Mat3 Rx = rot(Vec3(0, 1, 0), M_PI / 2);  // axis along x (up to rounding)
  Mat3 Px;  // exact: body z → lab x
  Px << 0, 0, 1,  //
      0, 1, 0,    //
      -1, 0, 0;
  expect_pair(rod, I3, rod, Px, Vec3(0, 1, 2), true);  // skew, perpendicular, distance 1
  expect_pair(rod, I3, rod, Px, Vec3(0, up(1.0), 2), false);
  expect_pair(rod, I3, rod, Rx, Vec3(0, 1 - 1e-12, 2), true, false);
  // Endpoint to endpoint: A's top (0, 0, 5) and B's left end (3, 0, 9) are 5 apart.
  expect_pair(fat, I3, fat, Px, Vec3(8, 0, 9), true);
  expect_pair(fat, I3, fat, Px, Vec3(8, 0, up(9.0)), false);
  // Endpoint of B against the interior of A.
  expect_pair(rod, I3, rod, Px, Vec3(6, 0, 2), true);
  expect_pair(rod, I3, rod, Px, Vec3(up(6.0), 0, 2), false);
  // A zero-length spherocylinder is a sphere.
  const Shape ball = Shape::spherocylinder(0, 1);
  expect_pair(ball, Rx, rod, I3, Vec3(0, 0, 6), true);
  expect_pair(ball, Rx, rod, I3, Vec3(0, 0, up(6.0)), false);
  expect_pair(ball, Rx, ball, I3, Vec3(0, 1, 0), true);
}

TEST(Spherocylinder, Sphere) {
  const Shape rod = Shape::spherocylinder(10, 1), s = Shape::sphere(1.0), tiny = Shape::sphere(0.1);
  expect_pair(rod, I3, s, I3, Vec3(0, 0, 6), true);  // cap
  expect_pair(rod, I3, s, I3, Vec3(0, 0, -up(6.0)), false);
  expect_pair(rod, I3, s, I3, Vec3(-1, 0, 4.5), true);  // side
  expect_pair(rod, I3, s, I3, Vec3(0, up(1.0), -4.5), false);
  expect_pair(rod, I3, Shape::sphere(4.0), I3, Vec3(1.5, 0, 7), true);  // cap, 3-4-5: (1.5, 2) from (0, 0, 5)
  expect_pair(rod, I3, Shape::sphere(4.0), I3, Vec3(1.5, 0, up(7.0)), false);
  expect_pair(rod, I3, tiny, I3, Vec3(0.1, 0.1, 4), true);     // nested
  expect_pair(rod, I3, tiny, I3, Vec3::Zero(), true);
}

// ---- dispatcher ----------------------------------------------------------------------------------

TEST(Dispatcher, SupportedPairsAndErrors) {
  using K = ShapeKind;
  const K kinds[3] = {K::Sphere, K::Cuboid, K::Spherocylinder};
  for (K a : kinds)
    for (K b : kinds) {
      const bool expected = !((a == K::Cuboid && b == K::Spherocylinder) || (a == K::Spherocylinder && b == K::Cuboid));
      EXPECT_EQ(overlap_supported(a, b), expected) << shape_kind_name(a) << " " << shape_kind_name(b);
      EXPECT_EQ(overlap_supported(a, b), overlap_supported(b, a));
    }
  static_assert(overlap_supported(ShapeKind::Sphere, ShapeKind::Cuboid));
  const Shape c = Shape::cuboid(1, 1, 1), r = Shape::spherocylinder(5, 1);
  EXPECT_THROW((void)overlap(c, I3, r, I3, Vec3(10, 0, 0)), std::invalid_argument);
  EXPECT_THROW((void)overlap(r, I3, c, I3, Vec3(10, 0, 0)), std::invalid_argument);
}

TEST(Dispatcher, BothOrdersMatchDirectKernels) {
  Rng rng(13, 0);
  const Shape board = Shape::cuboid(1, kSqrt12, 12), sph = Shape::sphere(3), rod = Shape::spherocylinder(8, 1);
  for (int n = 0; n < 5000; ++n) {
    const Mat3 Ra = random_rot(rng), Rb = random_rot(rng);
    const Vec3 t(rng.uniform(-10, 10), rng.uniform(-10, 10), rng.uniform(-10, 10));
    const bool cs = overlap_cuboid_sphere(Ra, board.half_extents(), t, 1.5);
    EXPECT_EQ(overlap(board, Ra, sph, Rb, t), cs);
    EXPECT_EQ(overlap(sph, Rb, board, Ra, Vec3(-t)), cs);
    const bool cc = overlap_cuboid_cuboid(board.half_extents(), Ra, board.half_extents(), Rb, t);
    EXPECT_EQ(overlap(board, Ra, board, Rb, t), cc);
    EXPECT_EQ(overlap(board, Rb, board, Ra, Vec3(-t)), cc);
    const bool rs = overlap_spherocylinder_sphere(4, 0.5, Ra.col(2), 1.5, t);
    EXPECT_EQ(overlap(rod, Ra, sph, Rb, t), rs);
    EXPECT_EQ(overlap(sph, Rb, rod, Ra, Vec3(-t)), rs);
    const bool rr = overlap_spherocylinder_spherocylinder(4, 0.5, Ra.col(2), 4, 0.5, Rb.col(2), t);
    EXPECT_EQ(overlap(rod, Ra, rod, Rb, t), rr);
    EXPECT_EQ(overlap(rod, Rb, rod, Ra, Vec3(-t)), rr);
    EXPECT_EQ(overlap(sph, Ra, sph, Rb, t), t.squaredNorm() <= 9.0);
  }
}

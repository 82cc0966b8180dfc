// Ellipsoid overlap kernels (geometry/ellipsoid_overlap.hpp) against the independent long-double
// references of tests/support/reference_ellipsoid.hpp, on 10^6 random pairs per kernel, plus
// closed-form contacts.
//
// Semi-axes come from five families: prolate (a, a, c) with c/a in [1, 10], oblate with c/a in
// [1/10, 1], triaxial with ratios down to 1/10, nearly spherical (relative deviations ±1e-9..1e-2)
// and exact spheres; the largest semi-axis is log-uniform in [0.3, 3] and the distinguished axis
// lands on a random body axis. Sphere radii are 0.05, 0.5, 1.5 or log-uniform in [0.025, 2.5].
// Orientations, the 1/8 of nearly parallel ellipsoid pairs and the placement (half of the pairs at
// (1 + δ) × the kernel's contact distance along a random direction, found by bisection, with |δ|
// log-uniform in [1e-9, 1e-2]; half uniform in the ball of 1.1 × the sum of circumradii) follow
// overlap_sampling.hpp.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>

#include "anisodyn/core/quaternion.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/geometry/ellipsoid_overlap.hpp"
#include "anisodyn/geometry/overlap.hpp"
#include "overlap_sampling.hpp"
#include "reference_ellipsoid.hpp"

namespace {

using anisodyn::Mat3;
using anisodyn::Quat;
using anisodyn::Rng;
using anisodyn::Vec3;
using anisodyn::overlap_ellipsoid_ellipsoid;
using anisodyn::overlap_ellipsoid_sphere;
using anisodyn::reference::Verdict;
using anisodyn::testing_support::log_uniform;
using anisodyn::testing_support::random_rotation;
using anisodyn::testing_support::random_unit_vector;

constexpr std::int64_t kPairs = 1'000'000;
constexpr std::uint64_t kSeed = 1;

Vec3 random_semi_axes(Rng& rng) {
  const double size = log_uniform(rng, 0.3, 3.0);
  const auto ratio = [&] { return rng.uniform() < 0.25 ? 0.1 : log_uniform(rng, 0.1, 1.0); };
  Vec3 s;
  switch (rng.index(5)) {
    case 0: { const double r = ratio(); s = Vec3(r, r, 1.0); break; }   // prolate
    case 1: s = Vec3(1.0, 1.0, ratio()); break;                         // oblate
    case 2: s = Vec3(1.0, ratio(), ratio()); break;                     // triaxial
    case 3:                                                             // nearly spherical
      for (int k = 0; k < 3; ++k) s[k] = 1.0 + (rng.uniform() < 0.5 ? -1.0 : 1.0) * log_uniform(rng, 1e-9, 1e-2);
      break;
    default: s = Vec3(1.0, 1.0, 1.0); break;                            // sphere
  }
  const int shift = static_cast<int>(rng.index(3));  // the distinguished axis onto x, y or z
  return size * Vec3(s[shift], s[(shift + 1) % 3], s[(shift + 2) % 3]);
}

double random_radius(Rng& rng) {
  if (rng.uniform() < 0.5) {
    const double r[3] = {0.05, 0.5, 1.5};
    return r[rng.index(3)];
  }
  return log_uniform(rng, 0.025, 2.5);
}

struct Pair {
  Vec3 a, b;  // semi-axes; b = (r, r, r) for an ellipsoid–sphere pair
  Mat3 Ra = Mat3::Identity(), Rb = Mat3::Identity();
  Vec3 t = Vec3::Zero();
  bool near_contact = false;
  double delta = 0.0;
};

/// Places the pair: near the kernel's contact along a random direction, or uniformly in a ball.
template <typename Kernel>
void place(Pair& p, Rng& rng, const Kernel& overlaps) {
  const Vec3 n = random_unit_vector(rng);
  const double outer = p.a.maxCoeff() + p.b.maxCoeff();
  if (rng.uniform() < 0.5) {
    p.near_contact = true;
    // Bisection between the touching inscribed and circumscribed spheres, to 1e-13 (relative):
    // far below the smallest |δ|.
    double lo = p.a.minCoeff() + p.b.minCoeff(), hi = outer;
    while (hi - lo > 1e-13 * hi) (overlaps(0.5 * (lo + hi) * n) ? lo : hi) = 0.5 * (lo + hi);
    p.delta = (rng.uniform() < 0.5 ? -1.0 : 1.0) * log_uniform(rng, 1e-9, 1e-2);
    p.t = 0.5 * (lo + hi) * (1.0 + p.delta) * n;
  } else {
    p.t = 1.1 * outer * std::cbrt(rng.uniform()) * n;
  }
}

Pair sample_ellipsoid_pair(Rng& rng) {
  Pair p;
  p.a = random_semi_axes(rng);
  p.b = random_semi_axes(rng);
  p.Ra = random_rotation(rng);
  p.Rb = random_rotation(rng);
  if (rng.uniform() < 0.125) {  // nearly parallel: identical, or rotated by 1e-12..1e-2 rad
    p.Rb = rng.uniform() < 0.25 ? p.Ra
                                : anisodyn::rotate_in_body_frame(Quat(p.Ra), log_uniform(rng, 1e-12, 1e-2) *
                                                                                 random_unit_vector(rng))
                                      .toRotationMatrix();
  }
  place(p, rng, [&](const Vec3& t) { return overlap_ellipsoid_ellipsoid(p.a, p.Ra, p.b, p.Rb, t); });
  return p;
}

Pair sample_ellipsoid_sphere(Rng& rng) {
  Pair p;
  p.a = random_semi_axes(rng);
  p.b = Vec3::Constant(random_radius(rng));
  p.Ra = random_rotation(rng);
  place(p, rng, [&](const Vec3& t) { return overlap_ellipsoid_sphere(p.a, p.Ra, p.b[0], t); });
  return p;
}

std::string describe(const Pair& p) {
  const Quat qa(p.Ra), qb(p.Rb);
  char buf[640];
  std::snprintf(buf, sizeof buf,
                "a=(%.17g %.17g %.17g) qa=(%.17g %.17g %.17g %.17g) b=(%.17g %.17g %.17g) "
                "qb=(%.17g %.17g %.17g %.17g) t=(%.17g %.17g %.17g) near_contact=%d delta=%.3g",
                p.a[0], p.a[1], p.a[2], qa.w(), qa.x(), qa.y(), qa.z(), p.b[0], p.b[1], p.b[2], qb.w(), qb.x(),
                qb.y(), qb.z(), p.t[0], p.t[1], p.t[2], int(p.near_contact), p.delta);
  return buf;
}

struct Stats {
  std::int64_t pairs = 0, overlapping = 0, near_contact = 0, undecided = 0;
  std::int64_t disagreements = 0;  // kernel against the reference, decided pairs only
  std::int64_t mismatches = 0;     // kernel against itself: swapped arguments, or sphere as an ellipsoid
};

/// Runs n pairs: the kernel `verdict(p)` and its second form `other(p)` must both equal the
/// reference wherever it decides, and each other everywhere.
template <typename Sample, typename Kernel, typename Other, typename Reference>
Stats run(const char* name, std::uint64_t stream, Sample sample, Kernel verdict, Other other, Reference reference) {
  Rng rng(kSeed, stream);
  Stats st;
  const auto start = std::chrono::steady_clock::now();
  for (std::int64_t i = 0; i < kPairs; ++i) {
    const Pair p = sample(rng);
    const bool k = verdict(p), k2 = other(p);
    const Verdict ref = reference(p);
    ++st.pairs;
    st.overlapping += k;
    st.near_contact += p.near_contact;
    if (k != k2 && st.mismatches++ < 10)
      std::printf("  MISMATCH %s: kernel=%d second form=%d  %s\n", name, int(k), int(k2), describe(p).c_str());
    if (ref == Verdict::Indeterminate) {
      if (st.undecided++ < 3)
        std::printf("  undecided %s: kernel=%d  %s\n", name, int(k), describe(p).c_str());
    } else if ((ref == Verdict::Overlap) != k) {
      if (st.disagreements++ < 10)
        std::printf("  DISAGREEMENT %s: kernel=%d reference=%s  %s\n", name, int(k),
                    anisodyn::reference::verdict_name(ref), describe(p).c_str());
    }
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("[%s] seed=%llu pairs=%lld overlapping=%.4f near_contact=%.4f undecided=%lld (%.2e) "
              "disagreements=%lld mismatches=%lld time=%.2fs\n",
              name, static_cast<unsigned long long>(kSeed), static_cast<long long>(st.pairs),
              double(st.overlapping) / double(st.pairs), double(st.near_contact) / double(st.pairs),
              static_cast<long long>(st.undecided), double(st.undecided) / double(st.pairs),
              static_cast<long long>(st.disagreements), static_cast<long long>(st.mismatches), secs);
  std::fflush(stdout);
  return st;
}

void expect_sound(const Stats& st) {
  EXPECT_EQ(st.pairs, kPairs);
  EXPECT_EQ(st.disagreements, 0);
  EXPECT_EQ(st.mismatches, 0);
  EXPECT_LT(double(st.undecided), 0.01 * double(st.pairs));
  // The sample must probe both verdicts and the contact region.
  const double f_overlap = double(st.overlapping) / double(st.pairs);
  EXPECT_GT(f_overlap, 0.2);
  EXPECT_LT(f_overlap, 0.8);
  EXPECT_NEAR(double(st.near_contact) / double(st.pairs), 0.5, 0.01);
}

}  // namespace

// The random-pair tests call the kernels through the shape dispatch (anisodyn::overlap on Shapes
// made from the shape list), the way MC and DMC call them, in both argument orders.
TEST(EllipsoidOverlap, RandomEllipsoidPairsAgreeWithTheAlgebraicReference) {
  using anisodyn::Shape;
  expect_sound(run(
      "ellipsoid-ellipsoid", 0, sample_ellipsoid_pair,
      [](const Pair& p) { return anisodyn::overlap(Shape::ellipsoid(p.a), p.Ra, Shape::ellipsoid(p.b), p.Rb, p.t); },
      [](const Pair& p) { return anisodyn::overlap(Shape::ellipsoid(p.b), p.Rb, Shape::ellipsoid(p.a), p.Ra, -p.t); },
      [](const Pair& p) { return anisodyn::reference::ellipsoid_ellipsoid(p.a, p.Ra, p.b, p.Rb, p.t); }));
}

TEST(EllipsoidOverlap, RandomEllipsoidSpherePairsAgreeWithTheDistanceReference) {
  // Second form: the sphere first (the dispatch swaps the bodies and flips t).
  using anisodyn::Shape;
  expect_sound(run(
      "ellipsoid-sphere", 1, sample_ellipsoid_sphere,
      [](const Pair& p) { return anisodyn::overlap(Shape::ellipsoid(p.a), p.Ra, Shape::sphere(2.0 * p.b[0]), p.Rb, p.t); },
      [](const Pair& p) { return anisodyn::overlap(Shape::sphere(2.0 * p.b[0]), p.Rb, Shape::ellipsoid(p.a), p.Ra, -p.t); },
      [](const Pair& p) { return anisodyn::reference::ellipsoid_sphere(p.a, p.Ra, p.b[0], p.t); }));
}

// ---- closed forms ---------------------------------------------------------------------------------

namespace {

/// A pair that touches at distance s along the unit vector n: the kernel's verdict must switch
/// within 1e-12 (relative) of s.
template <typename Kernel>
void expect_contact_at(double s, const Vec3& n, const Kernel& kernel) {
  EXPECT_TRUE(kernel((1.0 - 1e-12) * s * n)) << "s=" << s;
  EXPECT_FALSE(kernel((1.0 + 1e-12) * s * n)) << "s=" << s;
}

/// The same for a reference, 1e-6 either side.
template <typename Reference>
void expect_reference_contact_at(double s, const Vec3& n, const Reference& reference) {
  EXPECT_EQ(reference((1.0 - 1e-6) * s * n), Verdict::Overlap) << "s=" << s;
  EXPECT_EQ(reference((1.0 + 1e-6) * s * n), Verdict::Separated) << "s=" << s;
}

constexpr int kClosedFormCases = 10000;
constexpr int kReferenceCases = 2000;  // the first ones also check the reference (slower)

}  // namespace

TEST(EllipsoidOverlap, SpheresAsEllipsoidsTouchAtTheSumOfRadii) {
  Rng rng(kSeed, 10);
  for (int i = 0; i < kClosedFormCases; ++i) {
    const double ra = random_radius(rng), rb = random_radius(rng);
    const Mat3 Ra = random_rotation(rng), Rb = random_rotation(rng);
    const Vec3 n = random_unit_vector(rng);
    const Vec3 a = Vec3::Constant(ra), b = Vec3::Constant(rb);
    const auto ee = [&](const Vec3& t) { return overlap_ellipsoid_ellipsoid(a, Ra, b, Rb, t); };
    const auto es = [&](const Vec3& t) { return overlap_ellipsoid_sphere(a, Ra, rb, t); };
    const auto ee_ref = [&](const Vec3& t) { return anisodyn::reference::ellipsoid_ellipsoid(a, Ra, b, Rb, t); };
    const auto es_ref = [&](const Vec3& t) { return anisodyn::reference::ellipsoid_sphere(a, Ra, rb, t); };
    expect_contact_at(ra + rb, n, ee);
    expect_contact_at(ra + rb, n, es);
    const Vec3 t = rng.uniform(0.0, 1.5) * (ra + rb) * n;
    EXPECT_EQ(ee(t), t.norm() <= ra + rb);
    if (i < kReferenceCases) {
      expect_reference_contact_at(ra + rb, n, ee_ref);
      expect_reference_contact_at(ra + rb, n, es_ref);
      EXPECT_EQ(ee_ref(0.3 * (ra + rb) * n), Verdict::Overlap);
    }
  }
}

TEST(EllipsoidOverlap, AlignedEllipsoidsTouchAlongEachBodyAxisAtTheSumOfSemiAxes) {
  // Equal orientations and t along body axis k: the bodies touch at a_k + b_k (the vertical gap
  // between the two surfaces is convex and stationary on the axis); identical bodies at 2 a_k.
  Rng rng(kSeed, 11);
  for (int i = 0; i < kClosedFormCases; ++i) {
    const Vec3 a = random_semi_axes(rng);
    const Vec3 b = i % 2 == 0 ? a : random_semi_axes(rng);
    const Mat3 R = random_rotation(rng);
    const auto ab = [&](const Vec3& t) { return overlap_ellipsoid_ellipsoid(a, R, b, R, t); };
    const auto ba = [&](const Vec3& t) { return overlap_ellipsoid_ellipsoid(b, R, a, R, -t); };
    const auto ref = [&](const Vec3& t) { return anisodyn::reference::ellipsoid_ellipsoid(a, R, b, R, t); };
    for (int k = 0; k < 3; ++k) {
      const Vec3 axis = R.col(k) * (rng.uniform() < 0.5 ? -1.0 : 1.0);
      expect_contact_at(a[k] + b[k], axis, ab);
      expect_contact_at(a[k] + b[k], axis, ba);
      if (i < kReferenceCases) expect_reference_contact_at(a[k] + b[k], axis, ref);
    }
  }
}

TEST(EllipsoidOverlap, SphereOnABodyAxisTouchesAtSemiAxisPlusRadius) {
  Rng rng(kSeed, 12);
  for (int i = 0; i < kClosedFormCases; ++i) {
    const Vec3 a = random_semi_axes(rng);
    const double r = random_radius(rng);
    const Mat3 R = random_rotation(rng);
    const auto es = [&](const Vec3& t) { return overlap_ellipsoid_sphere(a, R, r, t); };
    const auto ref = [&](const Vec3& t) { return anisodyn::reference::ellipsoid_sphere(a, R, r, t); };
    for (int k = 0; k < 3; ++k) {
      const Vec3 axis = R.col(k) * (rng.uniform() < 0.5 ? -1.0 : 1.0);
      expect_contact_at(a[k] + r, axis, es);
      if (i < kReferenceCases) expect_reference_contact_at(a[k] + r, axis, ref);
    }
  }
}

// The random-pair test compares the two argument orders on all of its 10^6 pairs as well.
TEST(EllipsoidOverlap, SymmetricInTheArgumentOrder) {
  Rng rng(kSeed, 13);
  int mismatches = 0;
  for (int i = 0; i < 20000; ++i) {
    const Pair p = sample_ellipsoid_pair(rng);
    mismatches += overlap_ellipsoid_ellipsoid(p.a, p.Ra, p.b, p.Rb, p.t) !=
                  overlap_ellipsoid_ellipsoid(p.b, p.Rb, p.a, p.Ra, -p.t);
  }
  EXPECT_EQ(mismatches, 0);
}

#pragma once
#include <gtest/gtest.h>
// Random pairs of bodies for the overlap-kernel tests (test_overlap_random_pairs[_slow]).
//
// Shapes come from families that contain the project's real shapes (spec 10 §1): boards
// 1×√12×12, 1×1×12 and 1×8×12 and the unit cube, spheres of diameter 0.1, 1 and 3, spherocylinders
// with aspect (L + D)/D in [1, 20] (1 is the degenerate L = 0 body), plus random sizes.
// Orientations are uniform (Shoemake); 1/8 of the pairs of anisotropic bodies instead get nearly
// the same orientation (identical, or differing by a rotation of 1e-12..1e-2 rad), which exercises
// the parallel-axis paths.
// Half of the pairs are placed near contact: along a random direction n, the contact distance s_c
// is found by bisection with the kernel under test, and the pair is put at s_c (1 + δ) n with
// |δ| log-uniform in [1e-9, 1e-2] and a random sign. The other half have t uniform in the ball of
// radius 1.1 × (sum of circumradii).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include "anisodyn/core/quaternion.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/core/types.hpp"
#include "anisodyn/geometry/overlap.hpp"
#include "anisodyn/geometry/shape.hpp"
#include "reference_overlap.hpp"

namespace anisodyn::testing_support {

enum class PairFamily { SphereSphere, CuboidSphere, CuboidCuboid, SpherocylinderSpherocylinder, SpherocylinderSphere };

inline const char* family_name(PairFamily f) {
  switch (f) {
    case PairFamily::SphereSphere: return "sphere-sphere";
    case PairFamily::CuboidSphere: return "cuboid-sphere";
    case PairFamily::CuboidCuboid: return "cuboid-cuboid";
    case PairFamily::SpherocylinderSpherocylinder: return "spherocylinder-spherocylinder";
    case PairFamily::SpherocylinderSphere: return "spherocylinder-sphere";
  }
  return "?";
}

inline Mat3 random_rotation(Rng& rng) {
  const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
  return uniform_quaternion(u1, u2, u3).toRotationMatrix();
}

inline Vec3 random_unit_vector(Rng& rng) {
  const double z = rng.uniform(-1.0, 1.0), phi = 2.0 * M_PI * rng.uniform();
  const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
  return Vec3(s * std::cos(phi), s * std::sin(phi), z);
}

inline double log_uniform(Rng& rng, double lo, double hi) {
  return lo * std::exp(std::log(hi / lo) * rng.uniform());
}

inline Shape random_cuboid(Rng& rng) {
  if (rng.uniform() < 0.5) {
    switch (rng.index(4)) {
      case 0: return Shape::cuboid(1.0, std::sqrt(12.0), 12.0);
      case 1: return Shape::cuboid(1.0, 1.0, 12.0);
      case 2: return Shape::cuboid(1.0, 8.0, 12.0);
      default: return Shape::cuboid(1.0, 1.0, 1.0);
    }
  }
  // General cuboid, edges in [0.2, 12] (not necessarily sorted).
  return Shape::cuboid(log_uniform(rng, 0.2, 12.0), log_uniform(rng, 0.2, 12.0), log_uniform(rng, 0.2, 12.0));
}

inline Shape random_sphere(Rng& rng) {
  if (rng.uniform() < 0.5) {
    const double d[3] = {0.1, 1.0, 3.0};
    return Shape::sphere(d[rng.index(3)]);
  }
  return Shape::sphere(log_uniform(rng, 0.05, 5.0));
}

inline Shape random_spherocylinder(Rng& rng) {
  const double D = rng.uniform() < 0.5 ? 1.0 : log_uniform(rng, 0.2, 2.0);
  double aspect;  // (L + D) / D
  if (rng.uniform() < 0.25) {
    const double a[5] = {1.0, 2.0, 5.0, 10.0, 20.0};
    aspect = a[rng.index(5)];
  } else {
    aspect = rng.uniform(1.0, 20.0);
  }
  return Shape::spherocylinder((aspect - 1.0) * D, D);
}

struct PairSample {
  Shape a, b;
  Mat3 Ra = Mat3::Identity(), Rb = Mat3::Identity();
  Vec3 t = Vec3::Zero();   // r_b − r_a
  bool near_contact = false;
  bool near_aligned = false;
  double delta = 0.0;      // relative offset from contact (near-contact pairs)
};

/// Contact distance along the unit direction n, by bisection on the kernel's verdict.
inline double contact_distance(const Shape& a, const Mat3& Ra, const Shape& b, const Mat3& Rb, const Vec3& n) {
  double lo = 0.0;  // both bodies contain their centres: overlap
  double hi = 1.001 * (a.circumradius() + b.circumradius());
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (overlap(a, Ra, b, Rb, mid * n) ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

inline PairSample sample_pair(PairFamily family, Rng& rng) {
  PairSample p;
  switch (family) {
    case PairFamily::SphereSphere: p.a = random_sphere(rng); p.b = random_sphere(rng); break;
    case PairFamily::CuboidSphere: p.a = random_cuboid(rng); p.b = random_sphere(rng); break;
    case PairFamily::CuboidCuboid: p.a = random_cuboid(rng); p.b = random_cuboid(rng); break;
    case PairFamily::SpherocylinderSpherocylinder:
      p.a = random_spherocylinder(rng); p.b = random_spherocylinder(rng); break;
    case PairFamily::SpherocylinderSphere: p.a = random_spherocylinder(rng); p.b = random_sphere(rng); break;
  }
  p.Ra = random_rotation(rng);
  p.Rb = random_rotation(rng);
  if (p.a.is_anisotropic() && p.b.is_anisotropic() && rng.uniform() < 0.125) {
    p.near_aligned = true;
    if (rng.uniform() < 0.25) {
      p.Rb = p.Ra;
    } else {
      const Vec3 axis = random_unit_vector(rng);
      const Quat qa(p.Ra);
      p.Rb = rotate_in_body_frame(qa, log_uniform(rng, 1e-12, 1e-2) * axis).toRotationMatrix();
    }
  }
  const Vec3 n = random_unit_vector(rng);
  if (rng.uniform() < 0.5) {
    p.near_contact = true;
    const double sc = contact_distance(p.a, p.Ra, p.b, p.Rb, n);
    p.delta = (rng.uniform() < 0.5 ? -1.0 : 1.0) * log_uniform(rng, 1e-9, 1e-2);
    p.t = sc * (1.0 + p.delta) * n;
  } else {
    const double rmax = 1.1 * (p.a.circumradius() + p.b.circumradius());
    p.t = rmax * std::cbrt(rng.uniform()) * n;
  }
  return p;
}

/// Kernel verdict through the family's own kernel (not the dispatcher).
inline bool direct_kernel(PairFamily family, const PairSample& p) {
  switch (family) {
    case PairFamily::SphereSphere: return overlap_sphere_sphere(0.5 * p.a.diameter, 0.5 * p.b.diameter, p.t);
    case PairFamily::CuboidSphere: return overlap_cuboid_sphere(p.Ra, p.a.half_extents(), p.t, 0.5 * p.b.diameter);
    case PairFamily::CuboidCuboid:
      return overlap_cuboid_cuboid(p.a.half_extents(), p.Ra, p.b.half_extents(), p.Rb, p.t);
    case PairFamily::SpherocylinderSpherocylinder:
      return overlap_spherocylinder_spherocylinder(0.5 * p.a.length, 0.5 * p.a.diameter, p.Ra.col(2),
                                                   0.5 * p.b.length, 0.5 * p.b.diameter, p.Rb.col(2), p.t);
    case PairFamily::SpherocylinderSphere:
      return overlap_spherocylinder_sphere(0.5 * p.a.length, 0.5 * p.a.diameter, p.Ra.col(2), 0.5 * p.b.diameter,
                                           p.t);
  }
  return false;
}

struct RandomPairStats {
  std::int64_t pairs = 0, overlapping = 0, near_contact = 0, near_aligned = 0;
  std::int64_t indeterminate = 0, disagreements = 0, dispatcher_mismatches = 0;
  double max_dmin2_error = 0.0;  // cuboid–sphere: max |OCSI d_min² − reference| / (1 + d_min²)
};

inline std::string describe(const PairSample& p) {
  char buf[1024];
  const auto shape = [](const Shape& s) {
    char b[160];
    std::snprintf(b, sizeof b, "%s(edges %.17g %.17g %.17g, d %.17g, len %.17g)", shape_kind_name(s.kind),
                  s.edges[0], s.edges[1], s.edges[2], s.diameter, s.length);
    return std::string(b);
  };
  const Quat qa(p.Ra), qb(p.Rb);
  std::snprintf(buf, sizeof buf,
                "a=%s qa=(%.17g %.17g %.17g %.17g) b=%s qb=(%.17g %.17g %.17g %.17g) t=(%.17g %.17g %.17g) "
                "near_contact=%d delta=%.3g",
                shape(p.a).c_str(), qa.w(), qa.x(), qa.y(), qa.z(), shape(p.b).c_str(), qb.w(), qb.x(), qb.y(),
                qb.z(), p.t[0], p.t[1], p.t[2], int(p.near_contact), p.delta);
  return buf;
}

/// Samples n pairs of the family, compares kernel and reference, and prints a one-line summary.
/// The kernel is called through the dispatcher in a random argument order and directly; both must
/// agree. Disagreements with the reference (excluding indeterminate pairs) are printed (first 10).
inline RandomPairStats run_random_pairs(PairFamily family, std::int64_t n, std::uint64_t seed) {
  Rng rng(seed, static_cast<std::uint64_t>(family));
  RandomPairStats st;
  int printed = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    const PairSample p = sample_pair(family, rng);
    const bool direct = direct_kernel(family, p);
    const bool swapped = rng.uniform() < 0.5;
    const bool via_dispatch = swapped ? overlap(p.b, p.Rb, p.a, p.Ra, -p.t) : overlap(p.a, p.Ra, p.b, p.Rb, p.t);
    if (via_dispatch != direct) ++st.dispatcher_mismatches;
    const reference::Verdict ref = reference::overlap_verdict(p.a, p.Ra, p.b, p.Rb, p.t);
    ++st.pairs;
    st.overlapping += direct;
    st.near_contact += p.near_contact;
    st.near_aligned += p.near_aligned;
    if (ref == reference::Verdict::Indeterminate) {
      if (st.indeterminate++ < 3)
        std::printf("  indeterminate %s: kernel=%d  %s\n", family_name(family), int(direct), describe(p).c_str());
    } else if ((ref == reference::Verdict::Overlap) != direct) {
      ++st.disagreements;
      if (printed++ < 10)
        std::printf("  DISAGREEMENT %s: kernel=%d reference=%s  %s\n", family_name(family), int(direct),
                    reference::verdict_name(ref), describe(p).c_str());
    }
    if (family == PairFamily::CuboidSphere) {
      const double k = cuboid_sphere_dmin2(p.Ra, p.a.half_extents(), p.t);
      const reference::LD r =
          reference::cuboid_point_dist2(reference::ld(p.a.half_extents()), reference::ld(p.Ra), reference::ld(p.t));
      st.max_dmin2_error = std::max(st.max_dmin2_error, double(std::abs(k - r) / (1 + r)));
    }
  }
  std::printf("[%s] seed=%llu pairs=%lld overlapping=%.4f near_contact=%.4f near_aligned=%.4f indeterminate=%lld "
              "disagreements=%lld dispatcher_mismatches=%lld",
              family_name(family), static_cast<unsigned long long>(seed), static_cast<long long>(st.pairs),
              double(st.overlapping) / double(st.pairs), double(st.near_contact) / double(st.pairs),
              double(st.near_aligned) / double(st.pairs), static_cast<long long>(st.indeterminate),
              static_cast<long long>(st.disagreements), static_cast<long long>(st.dispatcher_mismatches));
  if (family == PairFamily::CuboidSphere) std::printf(" max_rel_dmin2_error=%.3g", st.max_dmin2_error);
  std::printf("\n");
  std::fflush(stdout);
  return st;
}

/// The checks shared by the fast (10^6) and slow (10^7) random-pair tests; use as
/// EXPECT_TRUE(random_pairs_agree(...)).
inline ::testing::AssertionResult random_pairs_agree(PairFamily family, std::int64_t pairs, std::uint64_t seed) {
  const RandomPairStats st = run_random_pairs(family, pairs, seed);
  const double f_overlap = double(st.overlapping) / double(st.pairs);
  const double f_near = double(st.near_contact) / double(st.pairs);
  auto failure = [&](const std::string& what) { return ::testing::AssertionFailure() << family_name(family) << ": " << what; };
  if (st.pairs != pairs) return failure("ran " + std::to_string(st.pairs) + " pairs");
  if (st.disagreements != 0) return failure(std::to_string(st.disagreements) + " disagreements with the reference");
  if (st.dispatcher_mismatches != 0) return failure(std::to_string(st.dispatcher_mismatches) + " dispatcher mismatches");
  // Indeterminate pairs (within the reference band of contact) are counted, never dropped silently.
  if (double(st.indeterminate) >= 1e-4 * double(pairs)) return failure(std::to_string(st.indeterminate) + " undecidable pairs");
  // The sample must really probe both verdicts and the contact region.
  if (f_overlap <= 0.2 || f_overlap >= 0.8) return failure("overlapping fraction " + std::to_string(f_overlap));
  if (std::abs(f_near - 0.5) > 0.01) return failure("near-contact fraction " + std::to_string(f_near));
  if (family == PairFamily::CuboidSphere && st.max_dmin2_error >= 1e-13)
    return failure("d_min^2 error " + std::to_string(st.max_dmin2_error));
  return ::testing::AssertionSuccess();
}

}  // namespace anisodyn::testing_support

// Core: periodic box, quaternion helpers and the counter-based RNG, against closed forms; the
// ordered sum against its chunked serial definition.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "anisodyn/core/box.hpp"
#include "anisodyn/core/ordered_sum.hpp"
#include "anisodyn/core/quaternion.hpp"
#include "anisodyn/core/rng.hpp"
#include "thread_count.hpp"

using namespace anisodyn;

TEST(Box, MinimumImageIsShortestOfAllImages) {
  Box box(Vec3(10, 20, 30));
  Rng rng(1, 0);
  for (int n = 0; n < 1000; ++n) {
    Vec3 d(rng.uniform(-50, 50), rng.uniform(-50, 50), rng.uniform(-50, 50));
    const Vec3 m = box.min_image(d);
    double best = 1e300;
    for (int a = -5; a <= 5; ++a)
      for (int b = -5; b <= 5; ++b)
        for (int c = -5; c <= 5; ++c)
          best = std::min(best, (d + Vec3(10 * a, 20 * b, 30 * c)).squaredNorm());
    EXPECT_NEAR(m.squaredNorm(), best, 1e-9);
    EXPECT_LE(std::abs(m.x()), 5.0 + 1e-12);
  }
}

TEST(Box, WrapKeepsUnwrappedPositionAndCountsImages) {
  Box box(Vec3(4, 5, 6));
  Vec3 r(-9.5, 17.0, 6.0);
  Int3 image(0, 0, 0);
  const Vec3 before = r;
  box.wrap(r, image);
  EXPECT_EQ(image, Int3(-3, 3, 1));
  for (int k = 0; k < 3; ++k) {
    EXPECT_GE(r[k], 0.0);
    EXPECT_LT(r[k], box.edges()[k]);
  }
  EXPECT_NEAR((box.unwrap(r, image) - before).norm(), 0.0, 1e-12);
}

TEST(Quaternion, RotationVectorMatchesAngleAxis) {
  const Vec3 axis = Vec3(1, 2, -0.5).normalized();
  for (double angle : {0.0, 1e-10, 1e-4, 0.3, 2.0, 3.1}) {
    const Quat q = quat_from_rotation_vector(angle * axis);
    const Mat3 expected = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    EXPECT_LT((q.toRotationMatrix() - expected).norm(), 1e-12) << angle;
  }
}

TEST(Quaternion, BodyFrameRotationTurnsAboutBodyAxis) {
  const Quat q = quat_from_rotation_vector(Vec3(0.3, -1.1, 0.7));
  const Mat3 O = q.toRotationMatrix();
  const Quat q2 = rotate_in_body_frame(q, Vec3(0, 0, 0.4));  // about body z
  const Mat3 O2 = q2.toRotationMatrix();
  EXPECT_LT((O2.col(2) - O.col(2)).norm(), 1e-12);             // body z axis unchanged
  EXPECT_NEAR(O2.col(0).dot(O.col(0)), std::cos(0.4), 1e-12);  // x turned by 0.4 rad
}

TEST(Quaternion, UniformRotationsHaveIsotropicAxes) {
  Rng rng(7, 3);
  const int n = 200000;
  double p2 = 0.0;
  Vec3 mean = Vec3::Zero();
  for (int i = 0; i < n; ++i) {
    const Quat q = uniform_quaternion(rng.uniform(), rng.uniform(), rng.uniform());
    const Vec3 e = q.toRotationMatrix().col(2);
    mean += e;
    p2 += 1.5 * e.z() * e.z() - 0.5;
  }
  // For uniform orientations <P2> = 0 with variance 1/5 per sample, <e> = 0 with variance 1/3.
  EXPECT_NEAR(p2 / n, 0.0, 4.0 * std::sqrt(0.2 / n));
  EXPECT_NEAR(mean.x() / n, 0.0, 4.0 * std::sqrt(1.0 / 3.0 / n));
}

TEST(Rng, SameKeySameSequenceDifferentStreamDifferentSequence) {
  Rng a(42, 1), b(42, 1), c(42, 2);
  int differ = 0;
  for (int i = 0; i < 100; ++i) {
    const double ua = a.uniform();
    EXPECT_EQ(ua, b.uniform());
    differ += (ua != c.uniform());
  }
  EXPECT_EQ(differ, 100);
}

TEST(Rng, RestoringStateContinuesTheSequence) {
  Rng a(5, 9);
  for (int i = 0; i < 7; ++i) a.uniform();  // stop mid-block
  Rng b(a.state());
  for (int i = 0; i < 20; ++i) EXPECT_EQ(a.bits(), b.bits());
}

TEST(Rng, UniformAndNormalMoments) {
  Rng rng(11, 0);
  const int n = 1000000;
  double su = 0, su2 = 0, sn = 0, sn2 = 0, sn4 = 0;
  for (int i = 0; i < n; ++i) {
    const double u = rng.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    su += u; su2 += u * u;
    const double g = rng.normal();
    sn += g; sn2 += g * g; sn4 += g * g * g * g;
  }
  // Tolerances: 5 standard errors of each sample moment.
  EXPECT_NEAR(su / n, 0.5, 5 * std::sqrt(1.0 / 12 / n));
  EXPECT_NEAR(su2 / n, 1.0 / 3, 5 * std::sqrt(4.0 / 45 / n));
  EXPECT_NEAR(sn / n, 0.0, 5 * std::sqrt(1.0 / n));
  EXPECT_NEAR(sn2 / n, 1.0, 5 * std::sqrt(2.0 / n));
  EXPECT_NEAR(sn4 / n, 3.0, 5 * std::sqrt(96.0 / n));
}

TEST(Rng, IndexIsUniform) {
  Rng rng(3, 3);
  const int n = 7, draws = 700000;
  std::vector<int> counts(n, 0);
  for (int i = 0; i < draws; ++i) counts[rng.index(n)]++;
  const double expected = double(draws) / n, sd = std::sqrt(expected * (1 - 1.0 / n));
  for (int c : counts) EXPECT_NEAR(c, expected, 5 * sd);
}

TEST(OrderedSum, TheSameBitsForAnyThreadCountAndTheChunkedSerialSum) {
  // Terms of mixed magnitude, so that another association would change the last bits.
  const std::size_t n = 10007;
  std::vector<double> term(n);
  Rng rng(3, 0);
  for (double& t : term) t = rng.uniform(-1.0, 1.0) * std::pow(10.0, rng.uniform(0.0, 4.0));
  // Written out here: chunks of 2048 in index order, the chunk sums in chunk order.
  double want = 0.0;
  for (std::size_t c = 0; c * 2048 < n; ++c) {
    double chunk = 0.0;
    for (std::size_t i = c * 2048; i < std::min(n, (c + 1) * 2048); ++i) chunk += term[i];
    want += chunk;
  }
  double plain = 0.0;
  for (const double t : term) plain += t;
  EXPECT_NE(want, plain) << "the terms do not tell one association from another";
  for (int threads : {1, 2, 3}) {
    const testing_support::ScopedThreadCount count(threads);
    EXPECT_EQ(ordered_sum(n, 0.0, [&](std::size_t i) { return term[i]; }), want) << threads << " threads";
    const Mat3 m = ordered_sum(n, Mat3::Zero().eval(), [&](std::size_t i) -> Mat3 { return term[i] * Mat3::Identity(); });
    EXPECT_EQ(m(1, 1), want);
  }
  EXPECT_EQ(ordered_sum(0, 1.5, [&](std::size_t) { return 1.0; }), 1.5) << "no terms: the zero given";
}

// Body-frame increments (analysis/body_frame_increments.hpp) against exact references: a turn by δ
// about one body axis gives −δ on that axis and 0 on the others; the projected angles match the
// body-frame rotation vector 2 vec(Δq) sign(Δq_w) to O(δ²) (spec 40 §8.4's cross-check); a
// synthetic rotational diffusion with known D_r,i is recovered by ⟨ΔΘ_i²⟩/(2τ) (spec 40 §8.4's
// synthetic test; 4 standard errors); a body stepping by a fixed body-frame displacement under the
// midpoint orientation gives it back exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "anisodyn/analysis/body_frame_increments.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

/// q ⊗ exp(θ/2): a turn by the body-frame rotation vector θ.
Quat turn_in_body(const Quat& q, const Vec3& theta) {
  const double angle = theta.norm();
  if (angle == 0.0) return q;
  return (q * Quat(Eigen::AngleAxisd(angle, theta / angle))).normalized();
}

}  // namespace

TEST(BodyFrame, ATurnAboutOneBodyAxisShowsOnThatAxisAlone) {
  const Quat q0 = Quat(Eigen::AngleAxisd(1.1, Vec3(0.3, -0.5, 0.8).normalized()));
  for (int axis = 0; axis < 3; ++axis) {
    const double delta = 0.07;
    Vec3 theta = Vec3::Zero();
    theta[axis] = delta;
    const std::vector<Quat> q{q0, turn_in_body(q0, theta)};
    const Vec3 angles = body_frame_rotation_angles(q)[0];
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(angles[k], k == axis ? -delta : 0.0, 1e-14) << axis << " " << k;
  }
}

TEST(BodyFrame, ProjectedAnglesMatchTheQuaternionRotationVector) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  Quat q = Quat::Identity();
  for (int n = 0; n < 200; ++n) {
    const double size = 0.01;
    const Vec3 theta = size * Vec3(normal(rng), normal(rng), normal(rng));
    const Quat next = turn_in_body(q, theta);
    const Quat dq = q.conjugate() * next;
    const Vec3 vector = 2.0 * (dq.w() < 0 ? -1.0 : 1.0) * Vec3(dq.x(), dq.y(), dq.z());
    const Vec3 angles = body_frame_rotation_angles(std::vector<Quat>{q, next})[0];
    EXPECT_LT((angles + vector).norm(), 5.0 * theta.squaredNorm() + 1e-15) << n;
    q = next;
  }
}

TEST(BodyFrame, SyntheticRotationalDiffusionIsRecovered) {
  // 400 bodies, 2000 intervals of dt = 1 with body-frame rotation vectors N(0, 2 D_i dt) on each
  // axis: D_r,i from the one-interval and ten-interval mean squares of the projected paths.
  const Vec3 D(1e-4, 2e-4, 5e-4);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  const int bodies = 400, intervals = 2000, lag = 10;
  Vec3 one = Vec3::Zero(), ten = Vec3::Zero(), one2 = Vec3::Zero(), ten2 = Vec3::Zero();
  double count_one = 0, count_ten = 0;
  for (int b = 0; b < bodies; ++b) {
    std::vector<Quat> q{Quat(Eigen::AngleAxisd(0.1 * b, Vec3(1, 1, 0).normalized()))};
    for (int n = 0; n < intervals; ++n)
      q.push_back(turn_in_body(q.back(), Vec3(std::sqrt(2 * D.x()) * normal(rng), std::sqrt(2 * D.y()) * normal(rng), std::sqrt(2 * D.z()) * normal(rng))));
    const std::vector<Vec3> path = accumulate_path(body_frame_rotation_angles(q));
    for (int n = 0; n + 1 < static_cast<int>(path.size()); ++n) {
      const Vec3 d = (path[static_cast<std::size_t>(n + 1)] - path[static_cast<std::size_t>(n)]).cwiseAbs2() / 2.0;
      one += d, one2 += d.cwiseAbs2(), ++count_one;
    }
    for (int n = 0; n + lag < static_cast<int>(path.size()); n += lag) {  // non-overlapping windows
      const Vec3 d = (path[static_cast<std::size_t>(n + lag)] - path[static_cast<std::size_t>(n)]).cwiseAbs2() / (2.0 * lag);
      ten += d, ten2 += d.cwiseAbs2(), ++count_ten;
    }
  }
  for (int k = 0; k < 3; ++k) {
    const double m1 = one[k] / count_one, se1 = std::sqrt((one2[k] / count_one - m1 * m1) / count_one);
    const double m10 = ten[k] / count_ten, se10 = std::sqrt((ten2[k] / count_ten - m10 * m10) / count_ten);
    EXPECT_LT(std::abs(m1 - D[k]), 4.0 * se1) << k;
    EXPECT_LT(std::abs(m10 - D[k]), 4.0 * se10) << k;
  }
}

TEST(BodyFrame, BodyFrameDisplacementsUseTheMidpointOrientation) {
  // A body turning at a constant rate about a fixed axis (so the slerp midpoint is the true one),
  // stepping by d in its own frame at each interval's midpoint orientation.
  const Vec3 d(0.3, -0.1, 0.05), axis = Vec3(0.2, 0.9, -0.4).normalized();
  std::vector<Vec3> x{Vec3(1, 2, 3)};
  std::vector<Quat> q{Quat(Eigen::AngleAxisd(0.4, Vec3(1, 0, 0)))};
  for (int n = 0; n < 50; ++n) {
    const Quat next = (Quat(Eigen::AngleAxisd(0.2, axis)) * q.back()).normalized();
    const Quat mid = (Quat(Eigen::AngleAxisd(0.1, axis)) * q.back()).normalized();
    x.push_back(x.back() + mid.toRotationMatrix() * d);
    q.push_back(next);
  }
  for (const Vec3& step : body_frame_displacements(x, q)) EXPECT_LT((step - d).norm(), 1e-13);
  const std::vector<Vec3> path = accumulate_path(body_frame_displacements(x, q));
  EXPECT_LT((path.back() - 50.0 * d).norm(), 1e-12);
}

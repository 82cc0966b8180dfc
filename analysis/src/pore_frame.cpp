#include "anisodyn/analysis/pore_frame.hpp"

#include <cmath>

namespace anisodyn::analysis {

std::size_t PoreFrameBins::bin(double beta) const { return beta <= 0.0 ? 0 : static_cast<std::size_t>(std::floor(beta / bin_width)); }

void PoreFrameBins::grow(std::size_t b) {
  while (count.size() <= b) {
    count.push_back(0);
    sum.emplace_back(lags, Vec3::Zero());
    sum2.emplace_back(lags, Vec3::Zero());
  }
}

void PoreFrameBins::add(std::size_t b, std::size_t lag, const Vec3& squared) {
  grow(b);
  sum[b][lag - 1] += squared;
  sum2[b][lag - 1] += squared.cwiseAbs2();
}

void PoreFrameBins::merge(const PoreFrameBins& other) {
  if (!other.count.empty()) grow(other.count.size() - 1);
  for (std::size_t b = 0; b < other.count.size(); ++b) {
    count[b] += other.count[b];
    for (std::size_t k = 0; k < lags; ++k) sum[b][k] += other.sum[b][k], sum2[b][k] += other.sum2[b][k];
  }
}

std::vector<Vec3> pore_frame_displacements(std::span<const Vec3> centre, const Vec3& axis) {
  std::vector<Vec3> out;
  for (std::size_t n = 1; n < centre.size(); ++n) {
    const Vec3 d = centre[n] - centre[n - 1];
    const double theta = std::atan2(centre[n - 1].y() - axis.y(), centre[n - 1].x() - axis.x());  // at t_{n−1} (spec 40 §9)
    const double c = std::cos(theta), s = std::sin(theta);
    out.emplace_back(c * d.x() + s * d.y(), -s * d.x() + c * d.y(), d.z());
  }
  return out;
}

void accumulate_pore_bins(std::span<const Vec3> centre, const Vec3& axis, double gap, PoreFrameBins& bins) {
  const std::vector<Vec3> step = pore_frame_displacements(centre, axis);
  for (std::size_t n = 0; n + bins.lags < centre.size(); ++n) {
    const double beta = std::hypot(centre[n].x() - axis.x(), centre[n].y() - axis.y()) / gap;
    const std::size_t b = bins.bin(beta);
    Vec3 path = Vec3::Zero();
    for (std::size_t k = 1; k <= bins.lags; ++k) {
      path += step[n + k - 1];
      bins.add(b, k, path.cwiseAbs2());
    }
    bins.count[b] += 1;
  }
}

}  // namespace anisodyn::analysis

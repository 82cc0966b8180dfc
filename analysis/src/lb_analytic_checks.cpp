#include "anisodyn/analysis/lb_analytic_checks.hpp"

#include <cmath>
#include <limits>
#include <random>

#include "anisodyn/analysis/pore_frame.hpp"
#include "anisodyn/analysis/raspberry_diffusion.hpp"
#include "anisodyn/core/statistics.hpp"
#include "anisodyn/lb/raspberry.hpp"

namespace anisodyn::analysis::checks {

namespace {

Recovered mean_of(const std::vector<double>& samples, double expected) {
  const MeanError m = mean_of_independent(samples);
  return {m.mean, m.error, expected};
}

}  // namespace

SyntheticBody synthetic_body(const Vec3& dt_body, const Vec3& dr_body, double alpha, int bodies, int intervals, std::uint64_t seed) {
  const Vec3 reference(std::cos(alpha), std::sin(alpha) * std::cos(0.3), std::sin(alpha) * std::sin(0.3));
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  std::vector<std::vector<double>> lag1(BodyLagCurves::kCurves);
  for (int b = 0; b < bodies; ++b) {
    std::vector<Vec3> x{Vec3::Zero()};
    std::vector<Quat> q{Quat(Eigen::AngleAxisd(0.37 * b, Vec3(1, 2, 3).normalized()))};
    for (int n = 0; n < intervals; ++n) {
      const Vec3 theta(std::sqrt(2 * dr_body.x()) * normal(rng), std::sqrt(2 * dr_body.y()) * normal(rng), std::sqrt(2 * dr_body.z()) * normal(rng));
      const Vec3 step(std::sqrt(2 * dt_body.x()) * normal(rng), std::sqrt(2 * dt_body.y()) * normal(rng), std::sqrt(2 * dt_body.z()) * normal(rng));
      // The step in the body frame halfway through the turn (the analysis's midpoint convention).
      const Quat mid = (q.back() * Quat(Eigen::AngleAxisd(0.5 * theta.norm(), theta.normalized()))).normalized();
      x.push_back(x.back() + mid.toRotationMatrix() * step);
      q.push_back((q.back() * Quat(Eigen::AngleAxisd(theta.norm(), theta.normalized()))).normalized());
    }
    const std::vector<double> flat = body_lag_curves(x, q, reference, 1).flatten();
    for (std::size_t c = 0; c < BodyLagCurves::kCurves; ++c) lag1[c].push_back(flat[c]);
  }
  const double sa = std::sin(alpha), ca = std::cos(alpha);
  SyntheticBody out;
  out.lab_msd = mean_of(lag1[0], 2 * dt_body.sum());
  out.reference_angle = mean_of(lag1[1], 2 * (dr_body.x() * sa * sa + dr_body.y() * (1 + ca * ca)));
  out.three_axis = mean_of(lag1[2], 4 * dr_body.sum());
  for (std::size_t i = 0; i < 3; ++i) {
    out.body_msd[i] = mean_of(lag1[3 + i], 2 * dt_body[static_cast<int>(i)]);
    out.body_angle[i] = mean_of(lag1[6 + i], 2 * dr_body[static_cast<int>(i)]);
  }
  return out;
}

PoreFrameFree pore_frame_free_motion(double D, double gap, int runs, int steps, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  PoreFrameBins bins;
  bins.bin_width = 0.1;
  bins.lags = 1;
  const Vec3 axis(0, 0, 0);
  for (int run = 0; run < runs; ++run) {
    const double r = gap * std::sqrt(uniform(rng)), phi = 2 * M_PI * uniform(rng);  // uniform in the disk
    std::vector<Vec3> x{Vec3(r * std::cos(phi), r * std::sin(phi), 0)};
    for (int n = 0; n < steps; ++n) x.push_back(x.back() + std::sqrt(2 * D) * Vec3(normal(rng), normal(rng), normal(rng)));
    accumulate_pore_bins(x, axis, gap, bins);
  }
  PoreFrameFree out;
  for (std::size_t b = 0; b < bins.count.size(); ++b) {
    const double n = static_cast<double>(bins.count[b]);
    out.beta.push_back((b + 0.5) * bins.bin_width);
    out.count.push_back(n);
    const bool checked = b >= 2 && n >= 2000;  // from β = 0.2: near the axis the radial direction turns fast
    for (int i = 0; i < 3; ++i) {
      const double mean = n > 0 ? bins.sum[b][0][i] / n : std::nan(""), var = n > 1 ? bins.sum2[b][0][i] / n - mean * mean : std::nan("");
      out.ratio[static_cast<std::size_t>(i)].push_back(mean / (2 * D));
      out.error[static_cast<std::size_t>(i)].push_back(std::sqrt(var / n) / (2 * D));  // one lag: independent steps
      if (checked) out.worst_pull = std::max(out.worst_pull, std::abs(mean - 2 * D) / std::sqrt(var / n));
    }
    out.bins_checked += checked;
  }
  return out;
}

NearestPoint nearest_point_against_brute_force(const Vec3& s, const Vec3& r) {
  const Vec3 p = lb::nearest_surface_point(s, r);
  const auto surface = [&](double th, double ph) { return Vec3(s.x() * std::cos(th), s.y() * std::sin(th) * std::cos(ph), s.z() * std::sin(th) * std::sin(ph)); };
  double best = std::numeric_limits<double>::infinity(), bt = 0, bp = 0;
  for (int i = 0; i <= 1000; ++i)
    for (int j = 0; j < 2000; ++j) {
      const double th = M_PI * i / 1000, ph = 2 * M_PI * j / 2000;
      const double d = (surface(th, ph) - r).squaredNorm();
      if (d < best) best = d, bt = th, bp = ph;
    }
  for (double scale = 1e-3; scale > 1e-9; scale *= 0.5)  // local refinement of the grid's best
    for (int i = -3; i <= 3; ++i)
      for (int j = -3; j <= 3; ++j) {
        const double th = bt + i * scale, ph = bp + j * scale;
        const double d = (surface(th, ph) - r).squaredNorm();
        if (d < best) best = d, bt = th, bp = ph;
      }
  return {(p - r).norm(), std::sqrt(best), std::abs(p.cwiseQuotient(s).squaredNorm() - 1.0), (p - surface(bt, bp)).norm()};
}

}  // namespace anisodyn::analysis::checks

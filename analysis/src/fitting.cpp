#include "anisodyn/analysis/fitting.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <limits>

namespace anisodyn::analysis {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

LinearFit fit_line(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& weights) {
  LinearFit fit;
  const bool weighted = !weights.empty();
  double sw = 0, sx = 0, sy = 0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (std::isnan(x[k]) || std::isnan(y[k])) continue;
    const double w = weighted ? weights[k] : 1.0;
    if (!(w > 0) || std::isinf(w)) continue;
    sw += w; sx += w * x[k]; sy += w * y[k]; ++n;
  }
  fit.points = n;
  if (n < 2) { fit.slope = fit.intercept = fit.slope_error = fit.intercept_error = fit.covariance = kNaN; return fit; }
  const double xm = sx / sw, ym = sy / sw;
  double sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (std::isnan(x[k]) || std::isnan(y[k])) continue;
    const double w = weighted ? weights[k] : 1.0;
    if (!(w > 0) || std::isinf(w)) continue;
    sxx += w * (x[k] - xm) * (x[k] - xm);
    sxy += w * (x[k] - xm) * (y[k] - ym);
  }
  fit.slope = sxy / sxx;
  fit.intercept = ym - fit.slope * xm;
  double scale = 1.0;  // weighted: errors from the weights; unweighted: residual variance
  if (!weighted) {
    double rss = 0;
    for (std::size_t k = 0; k < x.size(); ++k) {
      if (std::isnan(x[k]) || std::isnan(y[k])) continue;
      const double r = y[k] - fit.slope * x[k] - fit.intercept;
      rss += r * r;
    }
    scale = n > 2 ? rss / static_cast<double>(n - 2) : kNaN;
  }
  fit.slope_error = std::sqrt(scale / sxx);
  fit.intercept_error = std::sqrt(scale * (1.0 / sw + xm * xm / sxx));
  fit.covariance = -xm * scale / sxx;
  return fit;
}

LinearFit fit_proportional(const std::vector<double>& x, const std::vector<double>& y) {
  LinearFit fit;
  double sxx = 0, sxy = 0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (std::isnan(x[k]) || std::isnan(y[k])) continue;
    sxx += x[k] * x[k]; sxy += x[k] * y[k]; ++n;
  }
  fit.points = n;
  fit.slope = n ? sxy / sxx : kNaN;
  double rss = 0;
  for (std::size_t k = 0; k < x.size(); ++k)
    if (!std::isnan(x[k]) && !std::isnan(y[k])) rss += (y[k] - fit.slope * x[k]) * (y[k] - fit.slope * x[k]);
  fit.slope_error = n > 1 ? std::sqrt(rss / static_cast<double>(n - 1) / sxx) : kNaN;
  return fit;
}

namespace {

/// Least-squares polynomial of ln y in u = ln x − ln x0 over the window; coefficients c0 + c1 u (+ c2 u²).
bool local_polynomial(const std::vector<double>& x, const std::vector<double>& y, double x0, double half_width_decades,
                      int degree, Eigen::VectorXd& coeff) {
  const double half = half_width_decades * std::log(10.0);
  const double l0 = std::log(x0);
  std::vector<double> us, vs;
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (!(x[k] > 0) || !(y[k] > 0)) continue;
    const double u = std::log(x[k]) - l0;
    if (std::abs(u) <= half * (1 + 1e-12)) { us.push_back(u); vs.push_back(std::log(y[k])); }
  }
  if (us.size() < static_cast<std::size_t>(degree) + 2) return false;  // at least one residual degree of freedom
  Eigen::MatrixXd a(us.size(), degree + 1);
  Eigen::VectorXd b(us.size());
  for (std::size_t k = 0; k < us.size(); ++k) {
    for (int p = 0; p <= degree; ++p) a(static_cast<Eigen::Index>(k), p) = std::pow(us[k], p);
    b(static_cast<Eigen::Index>(k)) = vs[k];
  }
  coeff = a.colPivHouseholderQr().solve(b);
  return true;
}

}  // namespace

std::vector<double> local_log_slope(const std::vector<double>& x, const std::vector<double>& y, double half_width_decades,
                                    int degree) {
  std::vector<double> out(x.size(), kNaN);
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (!(x[k] > 0)) continue;
    Eigen::VectorXd c;
    if (local_polynomial(x, y, x[k], half_width_decades, degree, c) && c.size() > 1 && std::isfinite(c(1))) {
      out[k] = c(1);
      continue;
    }
    // too few points within the window: central (or one-sided at the ends) difference
    const std::size_t a = k > 0 ? k - 1 : k, b = k + 1 < x.size() ? k + 1 : k;
    if (a != b && x[a] > 0 && y[a] > 0 && y[b] > 0) out[k] = std::log(y[b] / y[a]) / std::log(x[b] / x[a]);
  }
  return out;
}

bool local_log_quadratic(const std::vector<double>& x, const std::vector<double>& y, double x0, double half_width_decades,
                         LogQuadratic& fit) {
  Eigen::VectorXd c;
  if (!local_polynomial(x, y, x0, half_width_decades, 2, c)) return false;
  fit.value = std::exp(c(0));
  fit.slope = c(1);
  fit.curvature = 2.0 * c(2);
  return true;
}

LinearFit fit_exponential(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<double> xs, ls;
  for (std::size_t k = 0; k < x.size(); ++k)
    if (y[k] > 0) { xs.push_back(x[k]); ls.push_back(std::log(y[k])); }
  return fit_line(xs, ls);
}

}  // namespace anisodyn::analysis

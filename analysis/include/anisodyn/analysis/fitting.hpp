#pragma once
// Generic fitting utilities (spec 50 §11): weighted linear least squares, log–log local slopes,
// and exponential decays by linear regression of ln y.
#include <cstddef>
#include <vector>

namespace anisodyn::analysis {

struct LinearFit {
  double slope = 0.0, intercept = 0.0;
  double slope_error = 0.0, intercept_error = 0.0, covariance = 0.0;
  std::size_t points = 0;
};

/// y = slope·x + intercept by least squares over the points with first ≤ index < last (all by
/// default). With weights w_k (1/variance), the errors are from the weights; without, from the
/// residual variance. Fewer than 2 points → InputError-free NaN fit (points = count).
LinearFit fit_line(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& weights = {});

/// Slope through the origin, y = slope·x, unweighted, with its error from the residuals.
LinearFit fit_proportional(const std::vector<double>& x, const std::vector<double>& y);

/// d ln y / d ln x at each point: the slope of a local least-squares polynomial (degree 1 or 2)
/// of ln y against ln x over the points within ±half_width decades. Points with y ≤ 0 are skipped;
/// NaN where fewer than degree + 1 (or 3 for degree 2) points fall in the window.
std::vector<double> local_log_slope(const std::vector<double>& x, const std::vector<double>& y, double half_width_decades,
                                    int degree = 1);

/// A local quadratic of ln y in u = ln x − ln x0: y at x0, the log slope d ln y/d ln x and the log
/// curvature d² ln y/d(ln x)² there.
struct LogQuadratic {
  double value = 0, slope = 0, curvature = 0;
};

/// Local quadratic fit of ln y against ln x around x0 (±half_width decades). Returns false when fewer
/// than 4 points are available (one residual degree of freedom).
bool local_log_quadratic(const std::vector<double>& x, const std::vector<double>& y, double x0, double half_width_decades,
                         LogQuadratic& fit);

/// y = A exp(−x/τ) from a linear fit of ln y over the points with y > 0; returns the fit of ln y
/// (slope = −1/τ).
LinearFit fit_exponential(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace anisodyn::analysis

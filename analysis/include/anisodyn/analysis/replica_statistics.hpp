#pragma once
// Mean and standard error over replicas (spec 50 §0: n − 1 denominator), with blocks of time
// origins standing in for replicas when there is only one replica, and the jackknife over
// replicas for derived quantities (fits, ratios).
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <vector>

namespace anisodyn::analysis {

/// Collects one curve (a vector of values on a common grid) per replica or block.
class CurveSamples {
 public:
  void add(std::vector<double> curve) { samples_.push_back(std::move(curve)); }
  std::size_t count() const { return samples_.size(); }
  const std::vector<std::vector<double>>& samples() const { return samples_; }

  /// Point-wise mean; NaN entries of a sample are skipped.
  std::vector<double> mean() const;
  /// Point-wise standard error of the mean, sd/√n with n − 1 in the variance; NaN for n < 2.
  std::vector<double> standard_error() const;

 private:
  std::vector<std::vector<double>> samples_;
};

struct Estimate {
  double value = std::numeric_limits<double>::quiet_NaN();
  double error = std::numeric_limits<double>::quiet_NaN();
};

/// Mean and standard error (n − 1) of scalar samples; error NaN for fewer than 2.
Estimate mean_and_error(const std::vector<double>& x);

/// Jackknife over samples: value = f(mean of all curves); error from the leave-one-out estimates
/// f(mean of the others), √((n − 1)/n Σ (f_k − f̄)²). Error NaN for fewer than 2 samples.
Estimate jackknife(const CurveSamples& samples, const std::function<double(const std::vector<double>&)>& f);

struct CurveEstimate {
  std::vector<double> value, error;
};

/// Point-wise jackknife of a derived curve g(mean sample) (e.g. a ratio of moments): value =
/// g(mean of all samples), error from the leave-one-out curves; errors NaN for fewer than 2.
CurveEstimate jackknife_curve(const CurveSamples& samples,
                              const std::function<std::vector<double>(const std::vector<double>&)>& g);

/// The mean of a set of curves.
std::vector<double> mean_curve(const std::vector<std::vector<double>>& curves);

}  // namespace anisodyn::analysis

#include "anisodyn/analysis/polygamma.hpp"

#include <cmath>
#include <limits>

namespace anisodyn::analysis {

namespace {
constexpr double kAsymptoticFrom = 12.0;
}

double digamma(double x) {
  if (!(x > 0)) return std::numeric_limits<double>::quiet_NaN();
  double shift = 0;
  for (; x < kAsymptoticFrom; x += 1) shift -= 1.0 / x;
  const double r = 1.0 / (x * x);
  // ln x − 1/(2x) − Σ B_2k/(2k x^2k), k = 1..6
  const double series = r * (1.0 / 12 - r * (1.0 / 120 - r * (1.0 / 252 - r * (1.0 / 240 - r * (1.0 / 132 - r * (691.0 / 32760))))));
  return shift + std::log(x) - 0.5 / x - series;
}

double trigamma(double x) {
  if (!(x > 0)) return std::numeric_limits<double>::quiet_NaN();
  double shift = 0;
  for (; x < kAsymptoticFrom; x += 1) shift += 1.0 / (x * x);
  const double r = 1.0 / (x * x);
  // 1/x + 1/(2x²) + Σ B_2k/x^(2k+1), k = 1..6
  const double series = (1.0 / x) * r * (1.0 / 6 - r * (1.0 / 30 - r * (1.0 / 42 - r * (1.0 / 30 - r * (5.0 / 66 - r * (691.0 / 2730))))));
  return shift + 1.0 / x + 0.5 * r + series;
}

}  // namespace anisodyn::analysis

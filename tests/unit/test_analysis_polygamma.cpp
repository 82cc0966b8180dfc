// Digamma and trigamma against closed-form values and against finite differences of std::lgamma
// (an independent implementation of ln Γ).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "anisodyn/analysis/polygamma.hpp"

using anisodyn::analysis::digamma;
using anisodyn::analysis::trigamma;

namespace {
constexpr double kEulerGamma = 0.57721566490153286061;
constexpr double kPi = std::numbers::pi;
}  // namespace

TEST(Polygamma, ClosedFormValues) {
  EXPECT_NEAR(digamma(1.0), -kEulerGamma, 1e-14);
  EXPECT_NEAR(digamma(0.5), -kEulerGamma - 2 * std::log(2.0), 1e-13);
  EXPECT_NEAR(digamma(1.5), 2 - kEulerGamma - 2 * std::log(2.0), 1e-14);
  EXPECT_NEAR(digamma(2.0), 1 - kEulerGamma, 1e-14);
  EXPECT_NEAR(trigamma(1.0), kPi * kPi / 6, 1e-13);
  EXPECT_NEAR(trigamma(0.5), kPi * kPi / 2, 1e-12);
  EXPECT_NEAR(trigamma(1.5), kPi * kPi / 2 - 4, 1e-13);
  EXPECT_NEAR(trigamma(2.0), kPi * kPi / 6 - 1, 1e-13);
}

TEST(Polygamma, DerivativesOfLogGammaByFiniteDifferences) {
  for (double x = 0.3; x < 40; x *= 1.37) {
    const double h = 1e-5 * x;
    const double d_lgamma = (std::lgamma(x + h) - std::lgamma(x - h)) / (2 * h);
    EXPECT_NEAR(digamma(x), d_lgamma, 1e-7 * std::max(1.0, std::abs(d_lgamma))) << "x = " << x;
    const double hd = 1e-4 * x;
    const double d_digamma = (digamma(x + hd) - digamma(x - hd)) / (2 * hd);
    EXPECT_NEAR(trigamma(x), d_digamma, 1e-7 * trigamma(x)) << "x = " << x;
  }
  // the recurrences the implementation uses internally, checked across the switch to the series
  for (double x : {11.5, 11.99, 12.0, 12.01}) {
    EXPECT_NEAR(digamma(x + 1) - digamma(x), 1 / x, 1e-14);
    EXPECT_NEAR(trigamma(x) - trigamma(x + 1), 1 / (x * x), 1e-15);
  }
  EXPECT_TRUE(std::isnan(digamma(0.0)));
  EXPECT_TRUE(std::isnan(trigamma(-1.0)));
}

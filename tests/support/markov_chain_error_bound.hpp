#pragma once
// Upper bound on the standard error of a Markov-chain average, for the statistical tests that
// compare an MC or DMC average with its exact Boltzmann value within 4 standard errors: a bound
// keeps a huge error bar (a broken estimator, a chain that does not move) from letting any value pass.
#include <cmath>
#include <cstddef>

namespace anisodyn::testing_support {

/// Integrated autocorrelation times allowed, in units of the chain's crossing time (the cycles it
/// needs to cross the width of the distribution it samples): a random-walk Metropolis chain
/// decorrelates in a few crossings, and the margin covers what a field's well does to the walk.
inline constexpr double kCrossingsPerCorrelation = 10.0;

/// The standard error of the mean of n per-cycle samples of an observable of variance `variance`
/// is √(variance · 2τ/n), τ the integrated autocorrelation time in cycles; τ is taken as
/// kCrossingsPerCorrelation · `crossing`.
inline double markov_chain_error_bound(double variance, double crossing, std::size_t n) {
  return std::sqrt(variance * 2.0 * kCrossingsPerCorrelation * crossing / static_cast<double>(n));
}

}  // namespace anisodyn::testing_support

#pragma once
// Digamma ψ(x) = d ln Γ(x)/dx and trigamma ψ₁(x) = dψ/dx for real x > 0, to ~1e-14 relative: the
// recurrences ψ(x) = ψ(x + 1) − 1/x, ψ₁(x) = ψ₁(x + 1) + 1/x² lift x above 12, where the asymptotic
// (Stirling) series converge quickly. The standard library has Γ but not its log derivatives; the
// second-order GSER (passive_microrheology.hpp) needs both at 1 + α.

namespace anisodyn::analysis {

double digamma(double x);
double trigamma(double x);

}  // namespace anisodyn::analysis

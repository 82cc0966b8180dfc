#include "anisodyn/interactions/mie_pairs.hpp"

namespace anisodyn {

double barker_henderson_ratio(const MieCore& core, double kT) {
  constexpr int kIntervals = 200000;  // even; Simpson's error is far below 1e-10 at this resolution
  const double x_max = core.cutoff_ratio();
  const double h = x_max / kIntervals;
  // Deep inside the core e^{−βU} underflows long before (σ/r)ⁿ would overflow: the integrand is 1.
  auto integrand = [&](double x) { return x <= 0.5 ? 1.0 : 1.0 - std::exp(-core.energy(x, 1.0) / kT); };
  double sum = integrand(0.0) + integrand(x_max);
  for (int k = 1; k < kIntervals; ++k) sum += (k % 2 ? 4.0 : 2.0) * integrand(k * h);
  return sum * h / 3.0;
}

}  // namespace anisodyn

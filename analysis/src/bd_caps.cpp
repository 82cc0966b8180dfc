#include "anisodyn/analysis/bd_caps.hpp"

namespace anisodyn::analysis {

std::optional<double> capped_torque_steps(const Trajectory& t) {
  const auto it = t.observables.find(kCappedObservable);
  if (it == t.observables.end() || it->second.width < 2) return std::nullopt;
  double sum = 0;
  for (std::size_t r = 0; r < it->second.time.size(); ++r) sum += it->second.value[r * it->second.width + 1];
  return sum;
}

}  // namespace anisodyn::analysis

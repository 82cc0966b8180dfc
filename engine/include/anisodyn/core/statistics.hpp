#pragma once
// Mean and standard error of a correlated time series by block averaging (Flyvbjerg & Petersen,
// J. Chem. Phys. 91, 461, 1989): the series is halved by pair-averaging until fewer than
// kMinBlocks blocks remain; the reported error is the largest estimate over the levels, which is
// the plateau value once blocks are longer than the correlation time (conservative otherwise).
#include <cmath>
#include <cstddef>
#include <vector>

namespace anisodyn {

struct MeanError {
  double mean = 0.0;
  double error = 0.0;       // standard error of the mean
  std::size_t samples = 0;  // length of the series
  std::size_t blocks = 0;   // number of blocks at the level that gave `error`
};

inline MeanError block_average(std::vector<double> x, std::size_t min_blocks = 16) {
  MeanError out;
  out.samples = x.size();
  if (x.empty()) return out;
  double sum = 0.0;
  for (double v : x) sum += v;
  out.mean = sum / static_cast<double>(x.size());
  out.blocks = x.size();
  while (x.size() >= min_blocks && x.size() >= 2) {
    const double n = static_cast<double>(x.size());
    double m = 0.0, c0 = 0.0;
    for (double v : x) m += v;
    m /= n;
    for (double v : x) c0 += (v - m) * (v - m);
    c0 /= n;
    const double se = std::sqrt(c0 / (n - 1.0));
    if (se >= out.error) { out.error = se; out.blocks = x.size(); }
    std::vector<double> half(x.size() / 2);
    for (std::size_t i = 0; i < half.size(); ++i) half[i] = 0.5 * (x[2 * i] + x[2 * i + 1]);
    x.swap(half);
  }
  return out;
}

}  // namespace anisodyn

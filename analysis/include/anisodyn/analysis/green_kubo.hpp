#pragma once
// Green–Kubo shear viscosity (spec 30 §7) from the stress autocorrelation an engine recorded
// (run/green_kubo.hpp: one row of stress_acf per block of the run):
//
//   η(t) = (V/kT) ∫₀ᵗ C(t') dt',   C = ⟨P_αβ(0) P_αβ(t')⟩ averaged over αβ = xy, xz, yz,
//
// the integral by the trapezoid rule on the multiple-tau lag grid. Each block of each replica gives
// its own η_b(t) and its plateau, the mean of η_b over the lags in [t_min, t_max]; the results are
// the mean over all blocks with the standard error of that mean. The same is done for each part of
// the stress on its own (its autocorrelation only: the parts' cross terms are not in it, so the
// parts do not add up to the total).
#include <cstddef>
#include <string>
#include <vector>

#include "anisodyn/core/statistics.hpp"

namespace anisodyn::analysis {

/// One run's record.
struct StressAcfRecord {
  std::string path;
  std::vector<double> lag_time;
  std::vector<std::string> parts;          // "total", then the engine's parts (kinetic, …)
  double volume = 0.0, kT = 0.0;
  std::vector<std::vector<double>> blocks;  // per block: [lags × (3 × parts)] row-major
};

/// Reads stress_acf, stress_acf_lag_time and their attributes; InputError naming the file when the
/// run has no Green–Kubo record.
StressAcfRecord read_stress_acf(const std::string& path);

struct GreenKuboSettings {
  double plateau_t_min = 2.0, plateau_t_max = 5.0;  // spec 30 §7
};

struct GreenKuboPart {
  std::string name;
  std::vector<double> acf, acf_error;  // C(t), mean over blocks, and its standard error
  std::vector<double> eta, eta_error;  // η(t)
  MeanError plateau;                   // over the blocks' plateau values
};

struct GreenKuboResult {
  std::vector<double> lag_time;
  std::vector<GreenKuboPart> parts;  // total first
  std::size_t blocks = 0, runs = 0, plateau_lags = 0;
};

class GreenKuboViscosity {
 public:
  explicit GreenKuboViscosity(GreenKuboSettings settings) : settings_(settings) {}

  /// Adds one run's blocks; every run must share the lag grid and parts of the first.
  void add(const StressAcfRecord& record);
  GreenKuboResult compute() const;

 private:
  GreenKuboSettings settings_;
  std::vector<double> lag_time_;
  std::vector<std::string> parts_;
  std::size_t runs_ = 0;
  /// Per block of any run, per part: C(t) and η(t) (3-component means).
  std::vector<std::vector<std::vector<double>>> acf_, eta_;
};

}  // namespace anisodyn::analysis

#pragma once
// The DMC time mapping and the balancing of the species' time steps (spec 10 §4.3–4.5).
//
// Each cycle advances Brownian time by Δt = δt_clock E_clock / 3, where E is the species'
// effective acceptance: its acceptance A, or (3/2)A_t − (1/2)A_0 for a pulled tracer (A_0: the
// fraction of tracer trials that pass the overlap test, or 1, or a value from a zero-force run).
// Balance means E_s δt_s = E_ref δt_ref for every species s, so all species advance the same
// Brownian time per cycle:
//   Equilibrium — the time steps are set once from a preliminary run and then stay fixed;
//   PerCycle    — they are re-imposed after every cycle (out-of-equilibrium runs);
//   None        — the time steps are inputs and are never changed.
// A species with few particles (< kFewTrials per cycle) gets noisy per-cycle acceptances; its
// estimate is an exponential moving average over `smoothing_cycles` cycles (PerCycle) or the
// cumulative mean since the start of production, seeded with the preliminary run (otherwise).
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/dmc/dmc_engine.hpp"

namespace anisodyn {

enum class BalanceMode { None, Equilibrium, PerCycle };
enum class TracerBathAcceptance { OverlapPass, One, Fixed };

struct TimeBalanceSettings {
  BalanceMode mode = BalanceMode::None;
  int reference = 0;       // species whose δt_MC is an input
  int clock = 0;           // species whose acceptance advances the clock
  int tracer_species = -1; // species of the pulled tracer, if any
  TracerBathAcceptance a0 = TracerBathAcceptance::OverlapPass;
  double a0_value = 1.0;   // for TracerBathAcceptance::Fixed
  double smoothing_cycles = 10.0;
  std::vector<std::size_t> species_counts;
};

/// Pooled counts behind a realised balance: per species Σ_cycles (tried × E)·δt and Σ tried, so that
/// E δt over many cycles is a ratio of sums (a mean of per-cycle ratios is dominated by cycles in
/// which a species with one or two trials had E near 0).
struct BalanceSums {
  std::vector<double> weighted_steps;   // Σ effective accepted × δt in force during the cycle
  std::vector<std::int64_t> tried;
  void clear(std::size_t species) {
    weighted_steps.assign(species, 0.0);
    tried.assign(species, 0);
  }
  nlohmann::json to_json() const { return {weighted_steps, tried}; }
  void from_json(const nlohmann::json& j) {
    weighted_steps = j.at(0).get<std::vector<double>>();
    tried = j.at(1).get<std::vector<std::int64_t>>();
  }
};

class TimeBalance {
 public:
  static constexpr std::size_t kFewTrials = 10;

  explicit TimeBalance(const TimeBalanceSettings& settings);
  const TimeBalanceSettings& settings() const { return settings_; }

  /// tried × E_s from counts of species s: the accepted count, or (3/2)·accepted − (1/2)·A_0·tried for
  /// the tracer. A difference lost in rounding is returned as exactly 0 (see realised balance).
  double effective_accepted(int s, const TrialCounts& c) const;
  /// E_s from counts of species s.
  double effective_acceptance(int s, const TrialCounts& c) const;
  /// Time steps with E_s δt_s = E_ref δt_ref, E from `counts` (e.g. totals of a preliminary run).
  std::vector<double> balanced_steps(const std::vector<TrialCounts>& counts, const std::vector<double>& dt) const;
  /// Realised balance E_s δt_s / (E_ref δt_ref) per species over the cycles pooled in `sums`; NaN for
  /// every species when the reference has no trial or no positive effective acceptance there (the
  /// ratio would say nothing, or blow up on a denominator that is zero but for rounding).
  std::vector<double> realised_balance(const struct BalanceSums& sums) const;

  /// Starts production: the smoothed estimates of few-particle species begin from `totals`.
  void seed(const std::vector<TrialCounts>& totals);
  /// After a production cycle: returns the Brownian time increment; in PerCycle mode also writes
  /// the rebalanced time steps into dt.
  double advance(const std::vector<TrialCounts>& cycle, std::vector<double>& dt);

  /// Adds one cycle's counts, run with time steps dt, to `sums`.
  void add_to(BalanceSums& sums, const std::vector<TrialCounts>& cycle, const std::vector<double>& dt) const;

  nlohmann::json checkpoint() const;
  void restore(const nlohmann::json& j);

 private:
  struct Estimate {
    double acceptance = 0.0, pass = 0.0;
    bool started = false;
    TrialCounts totals;
  };
  bool few(int s) const { return settings_.species_counts[static_cast<std::size_t>(s)] < kFewTrials; }
  double effective(int s, double acceptance, double pass) const;
  void update_estimate(int s, const TrialCounts& c);

  TimeBalanceSettings settings_;
  std::vector<Estimate> estimates_;
};

}  // namespace anisodyn

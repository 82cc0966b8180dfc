#include "anisodyn/dmc/time_balance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace anisodyn {

TimeBalance::TimeBalance(const TimeBalanceSettings& settings)
    : settings_(settings), estimates_(settings.species_counts.size()) {}

double TimeBalance::effective(int s, double acceptance, double pass) const {
  if (s != settings_.tracer_species) return acceptance;
  double a0 = pass;
  if (settings_.a0 == TracerBathAcceptance::One) a0 = 1.0;
  else if (settings_.a0 == TracerBathAcceptance::Fixed) a0 = settings_.a0_value;
  return 1.5 * acceptance - 0.5 * a0;
}

double TimeBalance::effective_accepted(int s, const TrialCounts& c) const {
  const auto accepted = static_cast<double>(c.accepted);
  if (s != settings_.tracer_species) return accepted;
  double bath = static_cast<double>(c.passed);  // A_0 · tried
  if (settings_.a0 == TracerBathAcceptance::One) bath = static_cast<double>(c.tried);
  else if (settings_.a0 == TracerBathAcceptance::Fixed) bath = settings_.a0_value * static_cast<double>(c.tried);
  // With integer counts (A_0 = pass fraction or 1) the difference is exact; with a fixed A_0 it can
  // be a rounding residue of a true zero, which must not become a huge ratio downstream.
  const double e = 1.5 * accepted - 0.5 * bath;
  return std::abs(e) <= 1e-12 * (1.5 * accepted + 0.5 * bath) ? 0.0 : e;
}

double TimeBalance::effective_acceptance(int s, const TrialCounts& c) const {
  return c.tried > 0 ? effective_accepted(s, c) / static_cast<double>(c.tried) : 0.0;
}

std::vector<double> TimeBalance::balanced_steps(const std::vector<TrialCounts>& counts, const std::vector<double>& dt) const {
  std::vector<double> out = dt;
  const int ref = settings_.reference;
  const double target = effective_acceptance(ref, counts[static_cast<std::size_t>(ref)]) * dt[static_cast<std::size_t>(ref)];
  for (std::size_t s = 0; s < dt.size(); ++s) {
    if (static_cast<int>(s) == ref || counts[s].tried == 0) continue;
    const double e = effective_acceptance(static_cast<int>(s), counts[s]);
    if (e > 0.0 && target > 0.0) out[s] = target / e;
  }
  return out;
}

void TimeBalance::add_to(BalanceSums& sums, const std::vector<TrialCounts>& cycle, const std::vector<double>& dt) const {
  if (sums.tried.size() != cycle.size()) sums.clear(cycle.size());
  for (std::size_t s = 0; s < cycle.size(); ++s) {
    sums.weighted_steps[s] += effective_accepted(static_cast<int>(s), cycle[s]) * dt[s];
    sums.tried[s] += cycle[s].tried;
  }
}

std::vector<double> TimeBalance::realised_balance(const BalanceSums& sums) const {
  const std::size_t n = sums.tried.size();
  auto step = [&](std::size_t s) { return sums.weighted_steps[s] / static_cast<double>(sums.tried[s]); };
  const auto ref = static_cast<std::size_t>(settings_.reference);
  std::vector<double> out(n, std::numeric_limits<double>::quiet_NaN());
  if (ref >= n || sums.tried[ref] == 0 || !(sums.weighted_steps[ref] > 0.0)) return out;
  const double base = step(ref);
  for (std::size_t s = 0; s < n; ++s)
    if (sums.tried[s] > 0) out[s] = step(s) / base;
  return out;
}

void TimeBalance::seed(const std::vector<TrialCounts>& totals) {
  for (std::size_t s = 0; s < estimates_.size(); ++s) {
    Estimate& e = estimates_[s];
    e = Estimate{};
    if (totals.size() > s && totals[s].tried > 0) {
      e.totals = totals[s];
      e.acceptance = totals[s].acceptance();
      e.pass = totals[s].pass_fraction();
      e.started = true;
    }
  }
}

void TimeBalance::update_estimate(int s, const TrialCounts& c) {
  Estimate& e = estimates_[static_cast<std::size_t>(s)];
  if (!few(s)) {  // enough trials every cycle: this cycle's values
    e.acceptance = c.acceptance();
    e.pass = c.pass_fraction();
    e.started = true;
    return;
  }
  if (c.tried == 0) return;
  if (settings_.mode == BalanceMode::PerCycle) {
    const double alpha = e.started ? 1.0 / settings_.smoothing_cycles : 1.0;
    e.acceptance += alpha * (c.acceptance() - e.acceptance);
    e.pass += alpha * (c.pass_fraction() - e.pass);
  } else {
    e.totals.add(c);
    e.acceptance = e.totals.acceptance();
    e.pass = e.totals.pass_fraction();
  }
  e.started = true;
}

double TimeBalance::advance(const std::vector<TrialCounts>& cycle, std::vector<double>& dt) {
  for (std::size_t s = 0; s < cycle.size(); ++s) update_estimate(static_cast<int>(s), cycle[s]);
  auto E = [&](int s) {
    const Estimate& e = estimates_[static_cast<std::size_t>(s)];
    return effective(s, e.acceptance, e.pass);
  };
  const int clock = settings_.clock;
  // Only a few-particle clock without a seed can give a negative increment (a lone rejected tracer
  // trial); time never runs backwards.
  const double dt_bd = std::max(0.0, dt[static_cast<std::size_t>(clock)] * E(clock) / 3.0);
  if (settings_.mode == BalanceMode::PerCycle) {
    const int ref = settings_.reference;
    const double target = E(ref) * dt[static_cast<std::size_t>(ref)];
    for (std::size_t s = 0; s < dt.size(); ++s) {
      if (static_cast<int>(s) == ref || !estimates_[s].started) continue;
      const double e = E(static_cast<int>(s));
      if (e > 0.0 && target > 0.0) dt[s] = target / e;
    }
  }
  return dt_bd;
}

nlohmann::json TimeBalance::checkpoint() const {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& e : estimates_)
    j.push_back({e.acceptance, e.pass, e.started, e.totals.tried, e.totals.passed, e.totals.accepted});
  return j;
}

void TimeBalance::restore(const nlohmann::json& j) {
  for (std::size_t s = 0; s < estimates_.size(); ++s) {
    const auto& r = j.at(s);
    Estimate& e = estimates_[s];
    e.acceptance = r[0].get<double>();
    e.pass = r[1].get<double>();
    e.started = r[2].get<bool>();
    e.totals = TrialCounts{r[3].get<std::int64_t>(), r[4].get<std::int64_t>(), r[5].get<std::int64_t>()};
  }
}

}  // namespace anisodyn

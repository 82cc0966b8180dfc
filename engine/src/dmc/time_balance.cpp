#include "anisodyn/dmc/time_balance.hpp"

#include <algorithm>

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

double TimeBalance::effective_acceptance(int s, const TrialCounts& c) const {
  return effective(s, c.acceptance(), c.pass_fraction());
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

std::vector<double> TimeBalance::realised_balance(const std::vector<TrialCounts>& counts, const std::vector<double>& dt) const {
  const int ref = settings_.reference;
  const double base = effective_acceptance(ref, counts[static_cast<std::size_t>(ref)]) * dt[static_cast<std::size_t>(ref)];
  std::vector<double> out(dt.size(), 0.0);
  for (std::size_t s = 0; s < dt.size(); ++s)
    out[s] = base > 0.0 ? effective_acceptance(static_cast<int>(s), counts[s]) * dt[s] / base : 0.0;
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

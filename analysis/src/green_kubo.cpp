#include "anisodyn/analysis/green_kubo.hpp"

#include <sstream>

#include "anisodyn/core/error.hpp"
#include "anisodyn/io/h5md.hpp"

namespace anisodyn::analysis {

namespace {

constexpr std::size_t kComponents = 3;  // xy, xz, yz

double number_attribute(const io::H5mdReader& r, const std::string& key) {
  const auto text = r.observable_attribute("stress_acf", key);
  if (!text) throw InputError(r.path(), "/observables/stress_acf@" + key, "expected the attribute " + key);
  try {
    return std::stod(*text);
  } catch (const std::exception&) {
    throw InputError(r.path(), "/observables/stress_acf@" + key, "expected a number, got '" + *text + "'");
  }
}

/// "total_xy, total_xz, total_yz, kinetic_xy, …" → total, kinetic, …
std::vector<std::string> parts_of(const std::string& channels, const std::string& path) {
  std::vector<std::string> names, parts;
  std::stringstream in(channels);
  for (std::string item; std::getline(in, item, ',');) {
    const auto first = item.find_first_not_of(' ');
    names.push_back(first == std::string::npos ? "" : item.substr(first));
  }
  if (names.empty() || names.size() % kComponents != 0)
    throw InputError(path, "/observables/stress_acf@channels", "expected xy, xz, yz of each part, got '" + channels + "'");
  for (std::size_t k = 0; k < names.size(); k += kComponents) {
    const std::string& n = names[k];
    if (n.size() < 4 || n.substr(n.size() - 3) != "_xy")
      throw InputError(path, "/observables/stress_acf@channels", "expected <part>_xy, got '" + n + "'");
    parts.push_back(n.substr(0, n.size() - 3));
  }
  return parts;
}

/// The 3-component mean of part k at every lag.
std::vector<double> part_acf(const std::vector<double>& block, std::size_t lags, std::size_t parts, std::size_t k) {
  std::vector<double> out(lags);
  const std::size_t width = kComponents * parts;
  for (std::size_t l = 0; l < lags; ++l) {
    const double* c = block.data() + l * width + kComponents * k;
    out[l] = (c[0] + c[1] + c[2]) / 3.0;
  }
  return out;
}

/// (V/kT) × the running trapezoid integral from lag 0.
std::vector<double> running_integral(const std::vector<double>& acf, const std::vector<double>& t, double prefactor) {
  std::vector<double> out(acf.size(), 0.0);
  for (std::size_t l = 1; l < acf.size(); ++l) out[l] = out[l - 1] + prefactor * 0.5 * (acf[l] + acf[l - 1]) * (t[l] - t[l - 1]);
  return out;
}

/// Mean and standard error over the blocks, lag by lag.
void across_blocks(const std::vector<std::vector<std::vector<double>>>& per_block, std::size_t part, std::vector<double>& mean,
                   std::vector<double>& error) {
  const std::size_t lags = per_block.front()[part].size();
  mean.assign(lags, 0.0);
  error.assign(lags, 0.0);
  std::vector<double> samples(per_block.size());
  for (std::size_t l = 0; l < lags; ++l) {
    for (std::size_t b = 0; b < per_block.size(); ++b) samples[b] = per_block[b][part][l];
    const MeanError m = mean_of_independent(samples);
    mean[l] = m.mean;
    error[l] = m.error;
  }
}

}  // namespace

StressAcfRecord read_stress_acf(const std::string& path) {
  const io::H5mdReader r(path);
  if (!r.has_observable("stress_acf"))
    throw InputError(path, "/observables/stress_acf", "no Green-Kubo record: run the engine with the green_kubo key");
  StressAcfRecord rec;
  rec.path = path;
  const auto channels = r.observable_attribute("stress_acf", "channels");
  if (!channels) throw InputError(path, "/observables/stress_acf@channels", "expected the attribute channels");
  rec.parts = parts_of(*channels, path);
  rec.volume = number_attribute(r, "volume");
  rec.kT = number_attribute(r, "kT");
  const auto acf = r.read_observable("stress_acf");
  const auto lag = r.read_observable("stress_acf_lag_time");
  if (lag.rows() != acf.rows() || lag.rows() == 0)
    throw InputError(path, "/observables/stress_acf_lag_time", "expected one row per row of stress_acf");
  rec.lag_time.assign(lag.value.begin(), lag.value.begin() + static_cast<std::ptrdiff_t>(lag.width));
  if (acf.width != lag.width * kComponents * rec.parts.size())
    throw InputError(path, "/observables/stress_acf/value", "expected lags x channels values per row");
  for (std::size_t b = 0; b < acf.rows(); ++b)
    rec.blocks.emplace_back(acf.value.begin() + static_cast<std::ptrdiff_t>(b * acf.width),
                            acf.value.begin() + static_cast<std::ptrdiff_t>((b + 1) * acf.width));
  return rec;
}

void GreenKuboViscosity::add(const StressAcfRecord& record) {
  if (runs_ == 0) {
    lag_time_ = record.lag_time;
    parts_ = record.parts;
  } else if (record.lag_time != lag_time_ || record.parts != parts_) {
    throw InputError(record.path, "/observables/stress_acf", "expected the lag grid and parts of the first input");
  }
  ++runs_;
  const double prefactor = record.volume / record.kT;
  for (const auto& block : record.blocks) {
    std::vector<std::vector<double>> acf, eta;
    for (std::size_t k = 0; k < parts_.size(); ++k) {
      acf.push_back(part_acf(block, lag_time_.size(), parts_.size(), k));
      eta.push_back(running_integral(acf.back(), lag_time_, prefactor));
    }
    acf_.push_back(std::move(acf));
    eta_.push_back(std::move(eta));
  }
}

GreenKuboResult GreenKuboViscosity::compute() const {
  GreenKuboResult r;
  r.lag_time = lag_time_;
  r.blocks = acf_.size();
  r.runs = runs_;
  std::vector<std::size_t> window;
  for (std::size_t l = 0; l < lag_time_.size(); ++l)
    if (lag_time_[l] >= settings_.plateau_t_min && lag_time_[l] <= settings_.plateau_t_max) window.push_back(l);
  r.plateau_lags = window.size();
  if (window.empty() || acf_.empty()) return r;
  for (std::size_t k = 0; k < parts_.size(); ++k) {
    GreenKuboPart part;
    part.name = parts_[k];
    across_blocks(acf_, k, part.acf, part.acf_error);
    across_blocks(eta_, k, part.eta, part.eta_error);
    std::vector<double> plateaus;
    for (const auto& block : eta_) {
      double sum = 0.0;
      for (const std::size_t l : window) sum += block[k][l];
      plateaus.push_back(sum / static_cast<double>(window.size()));
    }
    part.plateau = mean_of_independent(plateaus);
    r.parts.push_back(std::move(part));
  }
  return r;
}

}  // namespace anisodyn::analysis

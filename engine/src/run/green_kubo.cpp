#include "anisodyn/run/green_kubo.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "anisodyn/core/error.hpp"

namespace anisodyn::run {

namespace {

/// Levels of the grid so that its longest lag, (p − 1) m^{K−1} steps, reaches max_lag.
int levels_for(double max_lag, double time_step) {
  const double steps = max_lag / time_step;
  int levels = 1;
  double longest = GreenKuboRecorder::kLagsPerLevel - 1;
  while (longest < steps) {
    longest *= GreenKuboRecorder::kAveraging;
    ++levels;
  }
  return levels;
}

std::string exact(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

constexpr int kComponents = 3;  // xy, xz, yz

}  // namespace

std::optional<GreenKuboSettings> parse_green_kubo(tool::ConfigNode& cfg) {
  auto node = cfg.optional_object("green_kubo");
  if (!node) return std::nullopt;
  GreenKuboSettings s;
  s.blocks = static_cast<int>(node->positive_integer("blocks", s.blocks));
  if (s.blocks < 2) node->fail("blocks", "expected at least 2 blocks (the error bar is their spread)");
  s.max_lag = node->positive("max_lag", s.max_lag);
  node->finish();
  return s;
}

GreenKuboRecorder::GreenKuboRecorder(const GreenKuboSettings& settings, double time_step, std::int64_t total_steps,
                                     std::vector<std::string> parts, double volume, double kT, const std::string& config_file)
    : settings_(settings),
      time_step_(time_step),
      total_steps_(total_steps),
      parts_(std::move(parts)),
      volume_(volume),
      kT_(kT),
      correlator_(kComponents * (1 + static_cast<int>(parts_.size())), kLagsPerLevel, kAveraging, levels_for(settings.max_lag, time_step),
                  settings.blocks) {
  const double block_time = static_cast<double>(total_steps / settings.blocks) * time_step;
  if (block_time < settings.max_lag)
    throw InputError(config_file, "green_kubo.max_lag",
                     "expected blocks at least max_lag long: " + std::to_string(settings.blocks) + " blocks of this run last " +
                         std::to_string(block_time) + " each (a longer run, fewer blocks or a shorter max_lag)");
}

int GreenKuboRecorder::block_of(std::int64_t step) const {
  const std::int64_t b = (std::max<std::int64_t>(step, 1) - 1) * settings_.blocks / total_steps_;
  return static_cast<int>(std::min<std::int64_t>(b, settings_.blocks - 1));
}

std::int64_t GreenKuboRecorder::block_end(int block) const { return total_steps_ * (block + 1) / settings_.blocks; }

void GreenKuboRecorder::add(std::int64_t step, const std::vector<Mat3>& parts, io::H5mdWriter& out) {
  std::vector<double> values(static_cast<std::size_t>(correlator_.channels()));
  Mat3 total = Mat3::Zero();
  for (std::size_t k = 0; k < parts.size(); ++k) {
    total += parts[k];
    double* v = values.data() + kComponents * (k + 1);
    v[0] = parts[k](0, 1);
    v[1] = parts[k](0, 2);
    v[2] = parts[k](1, 2);
  }
  values[0] = total(0, 1);
  values[1] = total(0, 2);
  values[2] = total(1, 2);
  const int block = block_of(step);
  correlator_.add(values.data(), block);
  if (block < settings_.blocks - 1 && step == block_end(block)) write_block(block, step, out);
}

void GreenKuboRecorder::finish(std::int64_t step, io::H5mdWriter& out) {
  while (written_ < settings_.blocks) write_block(written_, step, out);
}

void GreenKuboRecorder::write_block(int block, std::int64_t step, io::H5mdWriter& out) {
  const double t = static_cast<double>(step) * time_step_;
  std::vector<double> lag_time;
  for (const std::int64_t lag : correlator_.lags()) lag_time.push_back(static_cast<double>(lag) * time_step_);
  std::vector<double> samples;
  for (const std::int64_t n : correlator_.counts(block)) samples.push_back(static_cast<double>(n));
  out.append_observable("stress_acf", step, t, correlator_.correlation(block));
  out.append_observable("stress_acf_samples", step, t, samples);
  out.append_observable("stress_acf_lag_time", step, t, lag_time);
  written_ = block + 1;
  // Set with every block (they replace): a resumed file may have lost them with the rows it dropped.
  std::string channels = "total_xy, total_xz, total_yz";
  for (const std::string& p : parts_) channels += ", " + p + "_xy, " + p + "_xz, " + p + "_yz";
  out.set_observable_attribute("stress_acf", "channels", channels);
  out.set_observable_attribute("stress_acf", "volume", exact(volume_));
  out.set_observable_attribute("stress_acf", "kT", exact(kT_));
  out.set_observable_attribute("stress_acf", "blocks", std::to_string(settings_.blocks));
  out.set_observable_attribute("stress_acf", "units", "(kT/r_c^3)^2");
  out.set_observable_attribute(
      "stress_acf", "definition",
      "one row per block of the run: <P_ab(t0) P_ab(t0 + t)> over the origins whose later sample lies in the block, at the lags of "
      "stress_acf_lag_time, [lags x channels] row-major; multiple-tau correlator (16 lags per level, averaging 2), P sampled every step");
  out.set_observable_attribute("stress_acf_samples", "definition", "products averaged at each lag, per block");
  out.set_observable_attribute("stress_acf_lag_time", "units", "tau");
  out.set_observable_attribute("stress_acf_lag_time", "definition", "the lags of stress_acf");
}

nlohmann::json GreenKuboRecorder::to_json() const {
  return {{"correlator", correlator_.to_json()}, {"written", written_}};
}

void GreenKuboRecorder::restore(const nlohmann::json& j) {
  correlator_.restore(j.at("correlator"));
  written_ = j.at("written").get<int>();
}

}  // namespace anisodyn::run

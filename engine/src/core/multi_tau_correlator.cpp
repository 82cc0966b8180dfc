#include "anisodyn/core/multi_tau_correlator.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace anisodyn {

MultiTauCorrelator::MultiTauCorrelator(int channels, int lags_per_level, int averaging, int levels, int blocks)
    : channels_(channels), p_(lags_per_level), m_(averaging), levels_(levels), blocks_(blocks) {
  if (channels < 1 || averaging < 2 || lags_per_level < averaging || lags_per_level % averaging != 0 || levels < 1 || blocks < 1)
    throw std::invalid_argument("MultiTauCorrelator: expected channels >= 1, averaging >= 2, lags per level a multiple of averaging, "
                                "levels >= 1, blocks >= 1");
  const auto c = static_cast<std::size_t>(channels);
  level_.resize(static_cast<std::size_t>(levels));
  for (Level& l : level_) {
    l.ring.assign(static_cast<std::size_t>(p_) * c, 0.0);
    l.accumulator.assign(c, 0.0);
  }
  const std::size_t slots = static_cast<std::size_t>(blocks) * static_cast<std::size_t>(levels) * static_cast<std::size_t>(p_);
  sums_.assign(slots * c, 0.0);
  counts_.assign(slots, 0);
}

std::size_t MultiTauCorrelator::slot(int block, int level, int j) const {
  return (static_cast<std::size_t>(block) * static_cast<std::size_t>(levels_) + static_cast<std::size_t>(level)) * static_cast<std::size_t>(p_) +
         static_cast<std::size_t>(j);
}

void MultiTauCorrelator::add(const double* values, int block) {
  if (block < 0 || block >= blocks_) throw std::out_of_range("MultiTauCorrelator::add: block " + std::to_string(block) + " out of range");
  push(0, values, block);
}

void MultiTauCorrelator::push(int k, const double* values, int block) {
  Level& l = level_[static_cast<std::size_t>(k)];
  const auto c = static_cast<std::size_t>(channels_);
  l.head = (l.head + 1) % p_;
  for (std::size_t ch = 0; ch < c; ++ch) l.ring[static_cast<std::size_t>(l.head) * c + ch] = values[ch];
  if (l.filled < p_) ++l.filled;
  // Lags below p/m at levels above 0 are covered, more finely, by the level below.
  const int first = k == 0 ? 0 : p_ / m_;
  for (int j = first; j < l.filled; ++j) {
    const std::size_t older = static_cast<std::size_t>((l.head - j + p_) % p_) * c;
    const std::size_t s = slot(block, k, j);
    double* sum = sums_.data() + s * c;
    for (std::size_t ch = 0; ch < c; ++ch) sum[ch] += values[ch] * l.ring[older + ch];
    counts_[s] += 1;
  }
  if (k + 1 == levels_) return;
  for (std::size_t ch = 0; ch < c; ++ch) l.accumulator[ch] += values[ch];
  if (++l.accumulated < m_) return;
  l.accumulated = 0;
  for (std::size_t ch = 0; ch < c; ++ch) l.accumulator[ch] /= static_cast<double>(m_);
  push(k + 1, l.accumulator.data(), block);  // copied into level k + 1's ring before anything else
  std::fill(l.accumulator.begin(), l.accumulator.end(), 0.0);
}

std::vector<std::int64_t> MultiTauCorrelator::lags() const {
  std::vector<std::int64_t> out;
  std::int64_t scale = 1;
  for (int k = 0; k < levels_; ++k, scale *= m_)
    for (int j = k == 0 ? 0 : p_ / m_; j < p_; ++j) out.push_back(scale * j);
  return out;
}

std::vector<double> MultiTauCorrelator::correlation(int block) const {
  const auto c = static_cast<std::size_t>(channels_);
  std::vector<double> out;
  for (int k = 0; k < levels_; ++k)
    for (int j = k == 0 ? 0 : p_ / m_; j < p_; ++j) {
      const std::size_t s = slot(block, k, j);
      const auto n = static_cast<double>(counts_[s]);
      for (std::size_t ch = 0; ch < c; ++ch) out.push_back(counts_[s] > 0 ? sums_[s * c + ch] / n : 0.0);
    }
  return out;
}

std::vector<std::int64_t> MultiTauCorrelator::counts(int block) const {
  std::vector<std::int64_t> out;
  for (int k = 0; k < levels_; ++k)
    for (int j = k == 0 ? 0 : p_ / m_; j < p_; ++j) out.push_back(counts_[slot(block, k, j)]);
  return out;
}

nlohmann::json MultiTauCorrelator::to_json() const {
  nlohmann::json levels = nlohmann::json::array();
  for (const Level& l : level_)
    levels.push_back({{"ring", l.ring}, {"filled", l.filled}, {"head", l.head}, {"accumulator", l.accumulator}, {"accumulated", l.accumulated}});
  return {{"shape", {channels_, p_, m_, levels_, blocks_}}, {"levels", levels}, {"sums", sums_}, {"counts", counts_}};
}

void MultiTauCorrelator::restore(const nlohmann::json& j) {
  if (j.at("shape") != nlohmann::json({channels_, p_, m_, levels_, blocks_}))
    throw std::invalid_argument("MultiTauCorrelator::restore: the checkpoint's correlator has another shape");
  for (std::size_t k = 0; k < level_.size(); ++k) {
    const auto& src = j.at("levels").at(k);
    Level& l = level_[k];
    l.ring = src.at("ring").get<std::vector<double>>();
    l.filled = src.at("filled").get<int>();
    l.head = src.at("head").get<int>();
    l.accumulator = src.at("accumulator").get<std::vector<double>>();
    l.accumulated = src.at("accumulated").get<int>();
  }
  sums_ = j.at("sums").get<std::vector<double>>();
  counts_ = j.at("counts").get<std::vector<std::int64_t>>();
}

}  // namespace anisodyn

#pragma once
// Multiple-tau autocorrelator (Ramírez, Sukumaran, Vorselaars & Likhtman, J. Chem. Phys. 133,
// 154103, 2010): the autocorrelation of a series sampled every step, at lags that grow
// geometrically, in memory and time independent of the run length. The Green–Kubo integrals of
// spec 30 §7 need every step of a 10⁷-step run; the raw series would be gigabytes.
//
// Level 0 holds the last p samples and correlates the newest with each: lags 0 … p − 1 steps.
// Every m samples of level k are averaged into one sample of level k + 1, whose lags j m^{k+1}
// (j = p/m … p − 1) continue the grid where level k's end. C(lag) is the sum of the products over
// all time origins divided by their count; at level k these are products of m^k-step averages, the
// usual approximation of the method, exact for lags of level 0.
//
// Each channel is correlated with itself. The sums go to the block the caller names (the block of
// the later sample), so that a run yields independent block estimates for its error bars while
// the shift registers run on across block boundaries.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

namespace anisodyn {

class MultiTauCorrelator {
 public:
  /// `channels` series; p lags per level (a multiple of m); m samples averaged per level;
  /// `levels` levels; `blocks` separate sums.
  MultiTauCorrelator(int channels, int lags_per_level, int averaging, int levels, int blocks);

  /// Adds the next sample (one value per channel) with its products into block `block`.
  void add(const double* values, int block);

  /// The lags of the grid, in samples, increasing.
  std::vector<std::int64_t> lags() const;
  /// Block b's correlation, [lag][channel] row-major, each the mean of its products (0 where none).
  std::vector<double> correlation(int block) const;
  /// Block b's number of products per lag.
  std::vector<std::int64_t> counts(int block) const;

  int channels() const { return channels_; }
  int blocks() const { return blocks_; }

  /// Everything, for a checkpoint that resumes bit for bit.
  nlohmann::json to_json() const;
  void restore(const nlohmann::json& j);

 private:
  struct Level {
    std::vector<double> ring;        // p samples × channels, newest at `head`
    int filled = 0;                  // samples in the ring (≤ p)
    int head = -1;
    std::vector<double> accumulator;  // sum of the samples towards the next level's one
    int accumulated = 0;
  };

  void push(int level, const double* values, int block);
  /// Index into sums_/counts_ of (block, level, j).
  std::size_t slot(int block, int level, int j) const;

  int channels_, p_, m_, levels_, blocks_;
  std::vector<Level> level_;
  std::vector<double> sums_;         // [block][level][j][channel]
  std::vector<std::int64_t> counts_;  // [block][level][j]
};

}  // namespace anisodyn

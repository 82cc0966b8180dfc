#pragma once
// The Green–Kubo record of a run (spec 30 §7): the off-diagonal pressure tensor sampled every step
// into a multiple-tau autocorrelator (core/multi_tau_correlator.hpp), one set of sums per block of
// the run, so that anisodyn-viscosity gets η(t) = (V/kT) ∫₀ᵗ ⟨P_αβ(0) P_αβ(t')⟩ dt' with block
// errors without the raw series. Engine-neutral: an engine hands over the parts of its pressure
// tensor each step (DPD: kinetic, conservative, dissipative, random).
//
// Channels: the total's xy, xz, yz, then the same three of each part. At the end of each block the
// block's correlation becomes one row of the vector observables
//   stress_acf          [lags × channels], row-major: the block's mean products
//   stress_acf_samples  [lags]: products per lag
//   stress_acf_lag_time [lags]: the lags in time units
// with attributes naming the channels, the volume, kT and the block layout. A row is written at the
// block's last step, so a resumed run drops and rewrites exactly the rows after its checkpoint.
//
// Configuration key (absent: no record):
//   "green_kubo": {"blocks": 10, "max_lag": 20}
// max_lag (time units) sets the number of levels: the grid reaches at least max_lag. 16 lags per
// level, averaging 2 (Ramírez et al. 2010's usual choice).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/core/multi_tau_correlator.hpp"
#include "anisodyn/core/types.hpp"
#include "anisodyn/io/h5md.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::run {

struct GreenKuboSettings {
  int blocks = 10;
  double max_lag = 20.0;  // time units
};

/// The optional `green_kubo` object of cfg.
std::optional<GreenKuboSettings> parse_green_kubo(tool::ConfigNode& cfg);

class GreenKuboRecorder {
 public:
  static constexpr int kLagsPerLevel = 16;
  static constexpr int kAveraging = 2;

  /// `total_steps` of the run at `time_step`; `parts` names the parts of the pressure tensor that
  /// add() receives. Throws InputError (naming green_kubo.blocks / max_lag of config_file) when a
  /// block would be shorter than max_lag.
  GreenKuboRecorder(const GreenKuboSettings& settings, double time_step, std::int64_t total_steps, std::vector<std::string> parts,
                    double volume, double kT, const std::string& config_file);

  /// The pressure tensor's parts at `step` (1 … total_steps); writes the block's rows when `step`
  /// ends a block.
  void add(std::int64_t step, const std::vector<Mat3>& parts, io::H5mdWriter& out);
  /// Writes the rows of every block not yet written (the run ended early or by rounding).
  void finish(std::int64_t step, io::H5mdWriter& out);

  nlohmann::json to_json() const;
  void restore(const nlohmann::json& j);

 private:
  int block_of(std::int64_t step) const;
  std::int64_t block_end(int block) const;
  void write_block(int block, std::int64_t step, io::H5mdWriter& out);

  GreenKuboSettings settings_;
  double time_step_;
  std::int64_t total_steps_;
  std::vector<std::string> parts_;
  double volume_, kT_;
  MultiTauCorrelator correlator_;
  int written_ = 0;  // blocks whose rows are in the output
};

}  // namespace anisodyn::run

#pragma once
// An anisodyn-dmc run: the preliminary balancing stage (equilibrium mode), then production over
// the field schedule, streaming frames and per-cycle observables to an H5MD writer, with
// checkpoints that let an interrupted run continue bit-for-bit.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/dmc/dmc_engine.hpp"
#include "anisodyn/dmc/dmc_protocol.hpp"
#include "anisodyn/dmc/time_balance.hpp"
#include "anisodyn/io/h5md.hpp"

namespace anisodyn {

/// Resumable position within the run (stored in checkpoints).
struct DmcCursor {
  bool production = false;
  int preliminary_iteration = 0;
  std::int64_t preliminary_cycle = 0;      // within the current iteration
  std::int64_t cycle = 0;                  // production cycles done
  double time = 0.0;                       // Brownian time of production
  std::size_t segment = 0;
  bool segment_started = false;
  double segment_start = 0.0, segment_end = 0.0;  // current segment, in its unit (cycles or τ)
  std::int64_t last_switch_cycle = 0;
  std::int64_t next_log_frame = 0;         // index k of the next logarithmic frame time
  std::int64_t next_time_frame = 1;        // index k of the next linear-in-time frame
  std::int64_t last_frame_cycle = -1;
};

class DmcRunner {
 public:
  /// Throws InputError for inconsistent settings (missing time steps or diffusion coefficients).
  DmcRunner(State& state, const DmcProtocol& protocol, const std::string& config_file, bool quiet);

  /// Runs to the end, writing frames and observables to `out`. `checkpoint` is called every
  /// `checkpoint_every` cycles (0 = never) and, after an interrupt request, before Interrupted is thrown.
  void run(io::H5mdWriter& out, std::int64_t checkpoint_every, const std::function<void()>& checkpoint);

  /// Production cycle of the last completed output row (−1 before production): rows after it are
  /// dropped when resuming.
  std::int64_t last_output_step() const { return cursor_.production ? cursor_.cycle : -1; }
  nlohmann::json checkpoint_state() const;
  /// Also sets the state's step and time to the checkpoint's production cycle and Brownian time.
  void restore(const nlohmann::json& j);
  const nlohmann::json& summary() const { return summary_; }
  const DmcEngine& engine() const { return engine_; }

 private:
  void configure_species();
  void run_preliminary(const std::function<void()>& tick);
  void start_segment(io::H5mdWriter& out);
  bool segment_done() const;
  /// Fraction of the schedule done, for progress reports.
  double schedule_fraction() const;
  void switch_field(io::H5mdWriter& out, bool on);
  void production_cycle(io::H5mdWriter& out);
  void observe(io::H5mdWriter& out);
  bool frame_due();
  void write_frame(io::H5mdWriter& out);
  void finish_summary();
  std::int64_t species_index(const std::string& name) const;

  State& state_;
  DmcProtocol protocol_;
  std::string config_file_;
  bool quiet_;
  DmcEngine engine_;
  std::unique_ptr<TimeBalance> balance_;
  DmcCursor cursor_;
  std::vector<double> dt_;
  std::vector<TrialCounts> preliminary_totals_, production_totals_, window_;
  BalanceSums window_balance_, production_balance_;  // realised balance per observation row, and over production
  std::int64_t window_cycles_ = 0;
  bool attributes_written_ = false;
  int tracer_species_ = -1;
  nlohmann::json summary_ = nlohmann::json::object();
};

}  // namespace anisodyn

#pragma once
// An anisodyn-dmc run: the preliminary balancing stage (equilibrium mode), then production by the
// shared production runner (run/production_runner.hpp), of which DMC is a client: one step is one
// cycle of N trial moves, its time the Brownian time the time balance assigns to it. Checkpoints
// let an interrupted run continue bit-for-bit.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/dmc/dmc_engine.hpp"
#include "anisodyn/dmc/dmc_protocol.hpp"
#include "anisodyn/dmc/time_balance.hpp"
#include "anisodyn/integrate/integrator.hpp"
#include "anisodyn/io/h5md.hpp"
#include "anisodyn/run/production_runner.hpp"

namespace anisodyn {

/// Where the run stands before production (stored in checkpoints); production keeps its own cursor.
struct DmcCursor {
  bool production = false;
  int preliminary_iteration = 0;
  std::int64_t preliminary_cycle = 0;  // within the current iteration
};

class DmcRunner : public run::ProductionClient {
 public:
  /// Throws InputError for inconsistent settings (missing time steps or diffusion coefficients).
  DmcRunner(State& state, const DmcProtocol& protocol, const std::string& config_file, bool quiet);

  /// Runs to the end, writing frames and observables to `out`. `checkpoint` is called every
  /// `checkpoint_every` cycles (0 = never) and, after an interrupt request, before Interrupted is thrown.
  void run(io::H5mdWriter& out, std::int64_t checkpoint_every, const std::function<void()>& checkpoint);

  /// Production cycle of the last completed output row (−1 before production): rows after it are
  /// dropped when resuming.
  std::int64_t last_output_step() const { return cursor_.production ? production_.step() : -1; }
  nlohmann::json checkpoint_state() const;
  /// Also sets the state's step and time to the checkpoint's production cycle and Brownian time.
  void restore(const nlohmann::json& j);
  const nlohmann::json& summary() const { return summary_; }
  const DmcEngine& engine() const { return engine_; }

 private:
  // run::ProductionClient
  double advance() override;
  void observe(io::H5mdWriter& out, std::int64_t step, double time) override;
  void after_step(io::H5mdWriter& out, std::int64_t step, double time) override;
  Vec3 switch_field(bool on, std::int64_t step) override;
  bool field_on() const override { return engine_.field_on(); }
  std::vector<io::ParticleElement> frame_elements() const override;

  void configure_species();
  void configure_fields();
  void run_preliminary(run::CheckpointClock& checkpoints);
  std::int64_t preliminary_cycles_done() const;
  void warn_about_tracer_validity();
  void finish_summary();
  std::int64_t species_index(const std::string& name) const;

  State& state_;
  DmcProtocol protocol_;
  std::string config_file_;
  bool quiet_;
  DmcEngine engine_;
  CycleIntegrator<DmcEngine> cycle_{engine_};
  std::unique_ptr<TimeBalance> balance_;
  DmcCursor cursor_;
  run::ProductionRunner production_;
  std::vector<double> dt_;
  std::vector<TrialCounts> preliminary_totals_, production_totals_, window_;
  BalanceSums window_balance_, production_balance_;  // realised balance per observation row, and over production
  bool attributes_written_ = false;
  int tracer_species_ = -1;
  nlohmann::json summary_ = nlohmann::json::object();
};

}  // namespace anisodyn

#pragma once
// An MC preparation run is a list of phases executed in order (spec 10 §3):
//   compress — NPT with βP raised stepwise until η ≥ target, then affine squeezes (≤ 0.1% in
//              volume, halved after each failure and doubled after each success, interleaved
//              with NVT sweeps) to exactly the target packing fraction;
//   npt      — constant βP, isotropic or per-axis box moves;
//   nvt      — constant volume.
// Any phase may tune move sizes towards the target acceptance (preparation only). Observables are
// sampled every `observe_every` cycles; each phase ends with a summary (means with block-averaged
// standard errors, the phase label from the Q tensors).
//
// The run is a client of the shared step loop (run/step_loop.hpp): a cycle is one step, its time
// the cycle count (MC has no physical time), observables and frames stream into the H5MD output
// as in every engine, and the loop's cursor is part of the checkpoint.
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/integrate/integrator.hpp"
#include "anisodyn/interactions/orientational_field.hpp"
#include "anisodyn/io/h5md.hpp"
#include "anisodyn/mc/mc_engine.hpp"
#include "anisodyn/run/checkpoint_clock.hpp"
#include "anisodyn/run/frame_rules.hpp"
#include "anisodyn/run/step_loop.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn {

struct McPhase {
  enum class Type { Compress, Npt, Nvt };
  Type type = Type::Nvt;
  std::string label;
  std::int64_t cycles = 0;         // npt, nvt
  bool tune = false;
  double pressure = 0.0;           // npt: βP
  BoxMoves box_moves = BoxMoves::Isotropic;
  // compress
  double target_packing_fraction = 0.0;
  std::optional<double> pressure_start;  // default: ideal-gas pressure at the target density
  double pressure_growth = 1.25;
  std::int64_t cycles_per_step = 200;
  std::int64_t max_cycles = 1000000;
  std::int64_t squeeze_sweeps = 5;
  double squeeze_window = 0.02;    // the ramp stops once η ≥ target·(1 − window); squeezes do the rest
  double plateau_tolerance = 0.005;  // βP grows only while a step raises η by less than this fraction
  std::string expect_phase;  // "", "isotropic" or "nematic": checked at the end of the phase
  // compress with method "quick": shrink by quick_step (relative volume), remove overlaps, repeat
  std::string method = "npt";
  double quick_step = 0.005;
};

struct McProtocol {
  std::uint64_t seed = 1;
  std::uint64_t replica = 0;  // random stream of the seed (--replica K): independent replicas
  double target_acceptance = 0.35;
  std::int64_t tune_every = 100;
  std::int64_t observe_every = 10;
  bool domain_sweeps = false;  // "sweeps": "domains" (mc/domain_sweep.hpp), else sequential
  run::FrameRules frames;  // none: the final frame only
  OrientationalField field;
  std::vector<McPhase> phases;
};

/// The samples of one observable in the current phase (for its summary); each row has `width` values.
struct PhaseSeries {
  std::vector<double> value;
  std::size_t width = 1;
};

/// Resumable position within the protocol (stored in checkpoints).
struct McCursor {
  std::size_t phase = 0;
  std::int64_t cycle_in_phase = 0;  // compress: cycles spent so far in the phase
  double compress_pressure = 0.0;   // current βP of a compress phase (0 = not started)
  bool squeezing = false;           // compress: pressure ramp done, squeezing to the exact target
  double quick_step = 0.0;          // quick compress: current relative volume step (0 = not started)
  double squeeze_step = 0.0;        // compress: current relative volume step of the squeeze (0 = not started)
};

class McRunner : public run::StepClient {
 public:
  McRunner(State& state, const McProtocol& protocol, bool quiet);

  /// Runs from the cursor to the end, writing observables and frames to `out`. `checkpoint` is
  /// called every `checkpoint_every` cycles (0 = never) and when an interrupt was requested (then
  /// Interrupted is thrown after it returns), only at cycles without overlaps: an interrupt during
  /// quick compression's overlap removal goes back to the configuration before that shrink.
  void run(io::H5mdWriter& out, std::int64_t checkpoint_every, const std::function<void()>& checkpoint);

  /// The cycle of the last completed output row: rows after it are dropped when resuming.
  std::int64_t last_output_step() const { return loop_.step(); }
  const nlohmann::json& summary() const { return summary_; }

  /// Engine state for checkpoints, and its inverse (also sets the state's step and time).
  nlohmann::json checkpoint_state() const;
  void restore(const nlohmann::json& engine_state);
  /// Resuming: the current phase's samples, for its summary, from the run's partial output (rows
  /// after the checkpoint's cycle, left by a crash, are not taken).
  void restore_phase_samples(const io::H5mdReader& partial);

 private:
  // run::StepClient
  double advance() override;
  double advance_steps(std::int64_t k) override;
  void observe(io::H5mdWriter& out, std::int64_t step, double time) override;
  /// Tunes the move sizes when the phase's cycle count has reached a tuning point.
  void tune_if_due();

  void run_fixed_phase(io::H5mdWriter& out, const McPhase& phase);
  void run_compress_phase(io::H5mdWriter& out, const McPhase& phase);
  void run_quick_compress(io::H5mdWriter& out, const McPhase& phase);
  void one_cycle(io::H5mdWriter& out);
  /// Up to `most` cycles of a fixed phase: with domain sweeps under NVT, as many as can run as one
  /// batch (McEngine::cycles, the same bits) before anything reads the state — an observation, a
  /// frame, tuning, a checkpoint; otherwise one.
  void cycles_at_once(io::H5mdWriter& out, std::int64_t most);
  /// Quick compression's last configuration without overlaps (before the shrink whose overlaps
  /// are being removed) and the runner's state then: where an interrupt goes back to.
  struct ValidPoint {
    Particles particles;
    Box box;
    nlohmann::json runner;
  };
  ValidPoint valid_point() const { return {state_.particles, state_.box, checkpoint_state()}; }
  /// Goes back to `p`, writes the checkpoint and throws Interrupted: an interrupt during overlap
  /// removal is honoured within a cycle, and the resumed run repeats that shrink the same way.
  [[noreturn]] void interrupt_at(const ValidPoint& p);
  void summarise_phase(const McPhase& phase, std::int64_t first_step);
  void record(io::H5mdWriter& out, const std::string& name, const std::vector<double>& values, const std::string& definition);

  State& state_;
  McProtocol protocol_;
  McEngine engine_;
  CycleIntegrator<McEngine> sweep_{engine_};
  bool quiet_;
  McCursor cursor_;
  run::StepLoop loop_;
  run::CheckpointClock* checkpoints_ = nullptr;  // during run()
  MoveCounters tune_mark_, sample_mark_;
  std::map<std::string, PhaseSeries> phase_samples_;
  std::set<std::string> described_;  // observables whose units and definition are written
  nlohmann::json summary_ = nlohmann::json::object();
};

}  // namespace anisodyn

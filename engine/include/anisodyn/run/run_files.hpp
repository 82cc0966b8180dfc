#pragma once
// The files of a resumable run, the same for every engine (docs/run.md): the output streams into
// <output>.partial and appears at <output> only when the run completes; checkpoints go to
// <output>.checkpoint.h5 (the state, the engine's state as JSON, and the engine's large arrays as
// datasets: an LB fluid's populations). Running the same command
// again finds the checkpoint, checks that it was written with the same parameters, and continues
// the partial output after the checkpoint's step, so that the result is bit for bit the
// uninterrupted run's. An interrupt (SIGINT/SIGTERM) writes a checkpoint and keeps the partial file.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/io/h5md.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn::run {

class RunFiles {
 public:
  /// Looks for the checkpoint of `output`. One written with other `parameters` → InputError
  /// naming it (the user deletes it to start afresh).
  RunFiles(std::string output, nlohmann::json parameters);

  bool resuming() const { return resuming_; }
  /// The checkpoint's state when resuming, else the last frame of `input`.
  State starting_state(const std::string& input) const;
  /// The engine state saved by the checkpoint (resuming only); its runner's part is "runner".
  const nlohmann::json& engine_state() const { return engine_state_; }
  const std::string& checkpoint_path() const { return checkpoint_path_; }
  /// An array the checkpoint holds (resuming only); missing → InputError naming the checkpoint.
  std::vector<double> checkpoint_array(const std::string& name) const;
  /// Resuming: a reader of the partial output as the interrupted run left it (to read back what
  /// an engine needs of its own output), before open() continues it.
  io::H5mdReader partial_output() const;

  /// Opens the output: a new file with `header`, or, resuming, the partial file continued after
  /// `last_step` (rows after it are dropped).
  io::H5mdWriter& open(const io::H5mdHeader& header, std::int64_t last_step);
  /// A checkpoint: `engine_state` into the output (which flushes it) and, with `state` and the
  /// arrays, into the checkpoint file (the arrays go there only: the output does not carry them).
  void checkpoint(const State& state, const nlohmann::json& engine_state, const io::CheckpointArrays& arrays = {});
  /// Runs `body` with the interrupt handlers installed; on an interrupt keeps the partial output
  /// for the resume and rethrows (exit 130).
  void run(const std::function<void(io::H5mdWriter&)>& body);
  /// Completes the run: the final engine state, the output renamed into place, the checkpoint removed.
  void commit(const nlohmann::json& engine_state);

  /// The whole life of an engine's output: open (after the runner's last_output_step() when
  /// resuming), runner.run(out, checkpoint_every, checkpoint) with checkpoints of `state` and
  /// {"runner": runner.checkpoint_state()} (and runner.checkpoint_arrays(), for a runner that has
  /// them), then commit.
  template <class Runner>
  void run_to_completion(const io::H5mdHeader& header, const State& state, Runner& runner, std::int64_t checkpoint_every) {
    const auto engine_state = [&] { return nlohmann::json{{"runner", runner.checkpoint_state()}}; };
    const auto arrays = [&] {
      if constexpr (requires { runner.checkpoint_arrays(); }) return runner.checkpoint_arrays();
      else return io::CheckpointArrays{};
    };
    open(header, runner.last_output_step());
    run([&](io::H5mdWriter& out) { runner.run(out, checkpoint_every, [&] { checkpoint(state, engine_state(), arrays()); }); });
    commit(engine_state());
  }

 private:
  std::string output_, checkpoint_path_;
  nlohmann::json parameters_;
  bool resuming_ = false;
  nlohmann::json engine_state_;
  std::optional<io::H5mdHeader> header_;
  std::optional<io::H5mdWriter> out_;
};

}  // namespace anisodyn::run

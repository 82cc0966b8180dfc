#include "anisodyn/run/run_files.hpp"

#include <filesystem>

#include "anisodyn/core/error.hpp"
#include "anisodyn/core/signals.hpp"

namespace anisodyn::run {

RunFiles::RunFiles(std::string output, nlohmann::json parameters)
    : output_(std::move(output)), checkpoint_path_(output_ + ".checkpoint.h5"), parameters_(std::move(parameters)) {
  resuming_ = std::filesystem::exists(checkpoint_path_);
  if (!resuming_) return;
  const io::H5mdReader checkpoint(checkpoint_path_);
  if (checkpoint.parameters() != parameters_)
    throw InputError(checkpoint_path_, "/parameters", "a checkpoint of the same configuration; this one was written with "
                                                      "different parameters: delete it to start afresh");
  const auto j = checkpoint.checkpoint();
  if (!j) throw InputError(checkpoint_path_, "/anisodyn/checkpoint", "an engine state");
  engine_state_ = *j;
}

State RunFiles::starting_state(const std::string& input) const {
  return io::H5mdReader(resuming_ ? checkpoint_path_ : input).read_frame(-1);
}

io::H5mdReader RunFiles::partial_output() const { return io::H5mdReader(output_ + ".partial"); }

io::H5mdWriter& RunFiles::open(const io::H5mdHeader& header, std::int64_t last_step) {
  header_ = header;
  if (resuming_) out_.emplace(io::H5mdWriter::resume(output_, last_step));
  else out_.emplace(output_, header);
  return *out_;
}

std::vector<double> RunFiles::checkpoint_array(const std::string& name) const {
  return io::H5mdReader(checkpoint_path_).checkpoint_array(name);
}

void RunFiles::checkpoint(const State& state, const nlohmann::json& engine_state, const io::CheckpointArrays& arrays) {
  out_->write_checkpoint(engine_state);  // flushes the streamed output first
  io::write_checkpoint_file(checkpoint_path_, *header_, state, engine_state, arrays);
}

void RunFiles::run(const std::function<void(io::H5mdWriter&)>& body) {
  install_interrupt_handlers();
  try {
    body(*out_);
  } catch (const Interrupted&) {
    out_->suspend();
    throw;
  }
}

void RunFiles::commit(const nlohmann::json& engine_state) {
  out_->write_checkpoint(engine_state);
  out_->commit();
  std::filesystem::remove(checkpoint_path_);
}

}  // namespace anisodyn::run

// Checkpoint files: one-frame H5MD files with the engine state (include/anisodyn/io/h5md.hpp).
#include "anisodyn/io/h5md.hpp"

#include "anisodyn/core/error.hpp"

namespace anisodyn::io {

// =====================================================================================================
// Checkpoint files
// =====================================================================================================

void write_checkpoint_file(const std::string& path, const H5mdHeader& header, const State& state,
                           const nlohmann::json& engine_state, const CheckpointArrays& arrays) {
  H5mdHeader h = header;
  if (h.species.empty()) h.species = state.species;
  h.frames_per_chunk = 1;
  H5mdWriter writer(path, h);
  writer.append_frame(state);
  writer.write_checkpoint(engine_state);
  for (const auto& [name, values] : arrays) writer.write_checkpoint_array(name, values);
  writer.commit();
}

std::pair<State, nlohmann::json> read_checkpoint_file(const std::string& path) {
  H5mdReader reader(path);
  auto engine_state = reader.checkpoint();
  if (!engine_state)
    throw InputError(path, "/anisodyn/checkpoint/engine_state", "missing required dataset (not a checkpoint file)");
  return {reader.read_frame(-1), std::move(*engine_state)};
}

}  // namespace anisodyn::io

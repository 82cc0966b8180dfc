#pragma once
// H5MD 1.1 trajectories, observables and checkpoints (HDF5 C API). The layout is documented in
// docs/file-format.md; in short:
//
//   /h5md                          attr version = [1, 1]; creator {name, version}; author {name}
//   /particles/all/box             attrs dimension = 3, boundary = periodic ×3
//   /particles/all/box/edges       {step, time, value [F,3,3]}  (diagonal matrix: MDAnalysis reads it)
//   /particles/all/position        {step, time, value [F,N,3]}  wrapped into [0, L)
//   /particles/all/image           {step, time, value [F,N,3]}  int32
//   /particles/all/orientation     {step, time, value [F,N,4]}  unit quaternion (w, x, y, z), body → lab
//   /particles/all/species         {step, time, value [F,N]}    int32 index into /parameters/species
//   /particles/all/id              {step, time, value [F,N]}    int64
//   /particles/all/velocity        {step, time, value [F,N,3]}  only for states that carry velocities
//   /particles/all/angular_momentum {step, time, value [F,N,3]} only for states that carry them (lab frame)
//   /particles/all/<extra>         {step, time, value [F,N,W]}  float64, engine-specific per-particle
//                                  data (e.g. DMC rotation vectors), see ParticleElement
//   /observables/<name>            {step, time, value [R] or [R,W]}
//   /parameters/config             JSON text: the stage's full parameters
//   /parameters/provenance         JSON text (tool/provenance.hpp)
//   /parameters/species/…          species table
//   /anisodyn/checkpoint/engine_state   JSON text (restart state of the engine)
//
// Units are reduced (σ, τ) and no `unit` attributes are written (MDAnalysis rejects unknown ones).
// All frame elements share one step and one time dataset (HDF5 hard links), as H5MD allows.
// Observables with fewer rows than the trajectory has frames are moved to /anisodyn/observables/
// on commit(), because MDAnalysis reads /observables/<name>/value[frame] for every frame;
// H5mdReader looks in both places.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/system/state.hpp"

namespace anisodyn::io {

inline constexpr const char* kParticleGroup = "all";
inline constexpr const char* kVelocityElement = "velocity";
inline constexpr const char* kAngularMomentumElement = "angular_momentum";

struct H5mdHeader {
  std::string creator = "anisodyn";
  std::string creator_version;  // empty → anisodyn::kVersion
  std::string author = "anisodyn user";
  nlohmann::json parameters;    // the stage's full parameters (null → "{}")
  nlohmann::json provenance;    // tool::make_provenance(…) (null → "{}")
  SpeciesTable species;         // empty → taken from the first frame's State
  std::size_t frames_per_chunk = 0;  // HDF5 chunking of frame data; 0 = automatic (~128 KiB chunks)
};

/// Engine-specific per-particle data stored with a frame as /particles/all/<name>, value [F, N, width].
struct ParticleElement {
  std::string name;
  std::size_t width = 1;
  const double* data = nullptr;  // N × width values, row-major
};

/// Writes an H5MD file to <path>.partial through tool::AtomicOutput; nothing appears at <path> before
/// commit(). Destroying the writer without commit() removes the partial file. The constructor
/// throws InputError (exit 2) for an unusable output path; HDF5 failures while writing and
/// programming errors (changing particle count, unknown species, decreasing step) throw
/// RuntimeFailure.
class H5mdWriter {
 public:
  H5mdWriter(const std::string& path, const H5mdHeader& header);
  H5mdWriter(H5mdWriter&&) noexcept;
  H5mdWriter& operator=(H5mdWriter&&) noexcept;
  ~H5mdWriter();

  /// Appends one frame: step = s.step, time = s.time, box edges, positions (as stored: wrapped),
  /// images, orientations (w, x, y, z), species and ids, and velocities and angular momenta when
  /// the state carries them. The particle count is fixed by the first frame; steps must not
  /// decrease.
  void append_frame(const State& s);
  /// The same, plus extra per-particle elements; every frame must carry the same set of elements.
  void append_frame(const State& s, const std::vector<ParticleElement>& extra);
  std::size_t frame_count() const;

  /// Scalar time series /observables/<name>; rows are buffered and flushed in blocks.
  void append_observable(const std::string& name, std::int64_t step, double time, double value);
  /// Vector-valued series (value [rows, width]); the width is fixed by the first row.
  void append_observable(const std::string& name, std::int64_t step, double time, const std::vector<double>& values);
  /// String attribute on the observable's group (e.g. "units", "definition"); replaces an old value.
  void set_observable_attribute(const std::string& name, const std::string& key, const std::string& value);

  /// /anisodyn/checkpoint/engine_state as JSON text (replaced on every call); flushes the file.
  void write_checkpoint(const nlohmann::json& engine_state);
  /// /anisodyn/checkpoint/arrays/<name>: a float64 array of an engine's restart state too large for
  /// JSON text (an LB fluid's populations); replaces an array of that name.
  void write_checkpoint_array(const std::string& name, const std::vector<double>& values);

  /// Flushes, closes and atomically renames <path>.partial to <path>. No calls are allowed after.
  void commit();

  /// For an interrupted run (exit 130): flushes and closes the file but keeps <path>.partial on
  /// disk so that resume() can continue it. No calls are allowed after.
  void suspend();

  /// Reopens <path>.partial (left by suspend(), or by a crash after write_checkpoint()) to continue
  /// a run restarted from the checkpoint taken at `last_step`: frames and observable rows with
  /// step > last_step are dropped, everything else is kept. No usable partial file → InputError.
  static H5mdWriter resume(const std::string& path, std::int64_t last_step);

  const std::string& path() const;
  const std::string& partial_path() const;

 private:
  struct Impl;
  explicit H5mdWriter(std::unique_ptr<Impl> impl);
  void append_elements(const State& s, const std::vector<ParticleElement>& extra);
  std::unique_ptr<Impl> impl_;
};

/// Frames first, first + stride, …, `count` of them: one regular HDF5 hyperslab along the frame
/// axis, so that a bulk read holds only the selected frames in memory.
struct FrameSlice {
  std::size_t first = 0, count = 0, stride = 1;
  std::size_t frame(std::size_t k) const { return first + k * stride; }
};

/// Reads files written by H5mdWriter (and other H5MD 1.1 files with particle group "all" and an
/// orthorhombic box). Problems with the file → InputError(path, "<HDF5 path>", "…") (exit 2).
class H5mdReader {
 public:
  explicit H5mdReader(const std::string& path);
  H5mdReader(H5mdReader&&) noexcept;
  H5mdReader& operator=(H5mdReader&&) noexcept;
  ~H5mdReader();

  const std::string& path() const;
  std::size_t frame_count() const;
  std::size_t particle_count() const;
  /// index < 0 counts from the end (-1 = last frame). Fills box, species table, particles
  /// (positions, images, orientations, species, ids; velocities and angular momenta when the file
  /// has them), step and time.
  State read_frame(std::ptrdiff_t index) const;
  std::vector<std::int64_t> frame_steps() const;
  /// Names of the per-particle elements beyond position, image, orientation, species and id:
  /// velocity and angular momentum when stored, and the extra elements (see ParticleElement).
  std::vector<std::string> particle_element_names() const;
  /// Row of an extra element at a frame: N × width values (width returned in `width`).
  std::vector<double> read_particle_element(const std::string& name, std::ptrdiff_t index, std::size_t& width) const;
  std::vector<double> frame_times() const;
  SpeciesTable species() const;

  /// Bulk reads for analysis (one HDF5 read each). All frames of a per-particle element
  /// ("position", "image", "orientation" or an extra element) converted to float64, row-major
  /// [F × N × width]; `width` is returned. A missing element or a bad shape → InputError.
  std::vector<double> read_element_frames(const std::string& element, std::size_t& width) const;
  /// The same for the frames of `frames` only, [count × N × width].
  std::vector<double> read_element_frames(const std::string& element, std::size_t& width, const FrameSlice& frames) const;
  /// All frames of an integer per-particle element ("species", "id"), [F × N].
  std::vector<std::int64_t> read_integer_element_frames(const std::string& element) const;
  /// The same for the frames of `frames` only, [count × N].
  std::vector<std::int64_t> read_integer_element_frames(const std::string& element, const FrameSlice& frames) const;
  /// Box edges of every frame (vector or diagonal-matrix form), [F × 3].
  std::vector<double> box_edges_frames() const;

  bool has_observable(const std::string& name) const;
  std::vector<std::string> observable_names() const;
  struct Series {
    std::vector<std::int64_t> step;
    std::vector<double> time;
    std::vector<double> value;  // row-major [rows × width]
    std::size_t width = 1;
    std::size_t rows() const { return step.size(); }
  };
  Series read_observable(const std::string& name) const;
  /// String attribute of an observable's group, if present.
  std::optional<std::string> observable_attribute(const std::string& name, const std::string& key) const;

  nlohmann::json parameters() const;
  nlohmann::json provenance() const;
  /// /anisodyn/checkpoint/engine_state, if present.
  std::optional<nlohmann::json> checkpoint() const;
  /// /anisodyn/checkpoint/arrays/<name> (write_checkpoint_array); missing → InputError.
  std::vector<double> checkpoint_array(const std::string& name) const;

 private:
  /// Velocities and angular momenta of `frame` into p, for the elements the file has.
  void read_motion(Particles& p, std::size_t frame) const;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Named float64 arrays of an engine's restart state (H5mdWriter::write_checkpoint_array).
using CheckpointArrays = std::vector<std::pair<std::string, std::vector<double>>>;

/// A complete one-frame H5MD file holding `state`, plus /anisodyn/checkpoint/engine_state and the
/// arrays, written atomically (a crash while writing leaves the previous checkpoint file intact).
void write_checkpoint_file(const std::string& path, const H5mdHeader& header, const State& state,
                           const nlohmann::json& engine_state, const CheckpointArrays& arrays = {});
/// The state (last frame) and engine state of a checkpoint file. No checkpoint group → InputError.
std::pair<State, nlohmann::json> read_checkpoint_file(const std::string& path);

}  // namespace anisodyn::io

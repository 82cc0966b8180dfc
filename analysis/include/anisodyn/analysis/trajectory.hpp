#pragma once
// One replica's trajectory in memory, read in bulk from an H5MD file, and the checks that make a
// set of replicas comparable (spec 50 §0). Positions are unwrapped (position + image·L); times
// must increase strictly. Stages process replicas one at a time (for_each_replica), so memory
// stays at one replica whatever the replica count. A time window (frame_window.hpp) limits what
// is read to the window's frames, and the observables to the window's times.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/analysis/frame_window.hpp"
#include "anisodyn/core/types.hpp"
#include "anisodyn/system/species.hpp"
#include "anisodyn/tool/unit_system.hpp"

namespace anisodyn::analysis {

/// What a stage reads besides times, box, species and ids.
struct TrajectoryNeeds {
  bool positions = false;
  bool orientations = false;
  std::vector<std::string> elements;  // extra per-particle elements, e.g. "rotation_vector"
  std::vector<std::string> optional_elements;  // loaded when the file has them
  std::vector<std::string> observables;  // optional observables to load when present
  /// Optional observables that list events (a state per row, the first row the initial state, e.g.
  /// field_switches): windowed, they keep as first row the state in force at the window's start.
  std::vector<std::string> event_observables;
  FrameWindow window;           // not given = every frame
  std::size_t min_frames = 1;   // frames the stage needs in a given window (fewer → InputError)
};

struct ObservableSeries {
  std::vector<double> time;
  std::vector<double> value;  // [rows × width]
  std::size_t width = 1;
};

struct Trajectory {
  std::string path;
  std::size_t frames = 0, particles = 0;
  std::vector<double> time;          // [F]
  std::vector<std::int64_t> step;    // [F]
  std::vector<std::size_t> frame_index;  // [F] index of each frame in the file (≠ f with a window)
  std::vector<double> box;           // [F × 3]
  std::vector<double> position;      // [F × N × 3], unwrapped
  std::vector<double> orientation;   // [F × N × 4], (w, x, y, z), body → lab
  std::vector<int> species;          // [N]
  std::vector<std::int64_t> id;      // [N]
  SpeciesTable species_table;
  std::map<std::string, std::pair<std::size_t, std::vector<double>>> elements;  // name → (width, [F × N × width])
  std::map<std::string, ObservableSeries> observables;
  nlohmann::json parameters;
  tool::UnitSystem units;  // the run's (its parameters' "units"; reduced if absent)

  Vec3 pos(std::size_t f, std::size_t i) const {
    const double* p = &position[3 * (f * particles + i)];
    return {p[0], p[1], p[2]};
  }
  Quat quat(std::size_t f, std::size_t i) const {
    const double* q = &orientation[4 * (f * particles + i)];
    return Quat(q[0], q[1], q[2], q[3]);
  }
  /// Body axis k (0, 1, 2 = body x, y, z; T, W, L for boards) of particle i at frame f, in the lab.
  Vec3 axis(std::size_t f, std::size_t i, int k) const;
  Vec3 box_edges(std::size_t f) const { return {box[3 * f], box[3 * f + 1], box[3 * f + 2]}; }
  /// Index in the file of loaded frame f (f itself for a trajectory built in memory).
  std::size_t file_frame(std::size_t f) const { return frame_index.empty() ? f : frame_index[f]; }
  /// Row of an extra element: width values of particle i at frame f.
  const double* element(const std::string& name, std::size_t f, std::size_t i) const;
  std::size_t element_width(const std::string& name) const;
  /// Index of a species by name (InputError naming `where` if unknown).
  int species_index(const std::string& name, const std::string& config_file, const std::string& where) const;
  /// Indices of the particles of species s (all particles for s < 0).
  std::vector<std::size_t> members(int s) const;
};

/// Reads a trajectory: the frames of needs.window on the file's own times. Missing datasets, a bad
/// shape or frames out of order → InputError naming the file and the HDF5 path.
Trajectory load_trajectory(const std::string& path, const TrajectoryNeeds& needs);
/// Reads the frames `frames` only (for_each_replica chooses them on the replicas' common grid).
Trajectory load_trajectory(const std::string& path, const TrajectoryNeeds& needs, const io::FrameSlice& frames);

/// Expands input patterns (shell globs or plain paths) in order; a glob matching nothing or a plain
/// path that does not exist → InputError(source, "", …). Duplicates are removed.
std::vector<std::string> expand_inputs(const std::vector<std::string>& patterns, const std::string& source);

/// With this tolerance replicas are analysed each on its own time axis: only their particles and
/// species must agree, and a window picks each replica's frames from its own times. For stages that
/// measure every replica on its own (a pulled tracer's drift), whose runs may end at different
/// mapped times and hold different numbers of frames.
constexpr double kIndependentTimes = std::numeric_limits<double>::infinity();

/// Replicas must agree on particle count, species of each particle, frame count, and the times of
/// the frames `compared` within `time_tolerance` of the time from the first frame to the last
/// compared one; otherwise → InputError naming both files.
void check_replica_matches(const Trajectory& first, const Trajectory& other, double time_tolerance,
                           const io::FrameSlice& compared);
/// The same over every frame.
void check_replica_matches(const Trajectory& first, const Trajectory& other, double time_tolerance = 0.05);

/// The frames a window chose and the replicas' common time grid (every frame) it chose them on.
struct FrameSelection {
  io::FrameSlice frames;
  std::vector<double> grid;
};

/// Loads each replica in turn (the frames of needs.window on the common grid), checks it against
/// the first and calls fn(trajectory, index). Returns the common time grid of the loaded frames:
/// the mean time stamp of each frame over the replicas (spec 50 §0). `selected`, if given, receives
/// the frames chosen and the grid they were chosen on.
std::vector<double> for_each_replica(const std::vector<std::string>& paths, const TrajectoryNeeds& needs,
                                     const std::function<void(const Trajectory&, std::size_t)>& fn,
                                     double time_tolerance = 0.05, FrameSelection* selected = nullptr);

}  // namespace anisodyn::analysis

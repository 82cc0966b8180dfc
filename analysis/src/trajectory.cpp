#include "anisodyn/analysis/trajectory.hpp"

#include <glob.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "anisodyn/core/error.hpp"
#include "anisodyn/io/h5md.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn::analysis {

Vec3 Trajectory::axis(std::size_t f, std::size_t i, int k) const { return quat(f, i).toRotationMatrix().col(k); }

const double* Trajectory::element(const std::string& name, std::size_t f, std::size_t i) const {
  const auto& [width, data] = elements.at(name);
  return &data[width * (f * particles + i)];
}

std::size_t Trajectory::element_width(const std::string& name) const { return elements.at(name).first; }

int Trajectory::species_index(const std::string& name, const std::string& config_file, const std::string& where) const {
  std::string known;
  for (std::size_t s = 0; s < species_table.size(); ++s) {
    if (species_table[s].name == name) return static_cast<int>(s);
    known += (known.empty() ? "" : ", ") + species_table[s].name;
  }
  throw InputError(config_file, where, "unknown species '" + name + "' in " + path + " (it has: " + known + ")");
}

std::vector<std::size_t> Trajectory::members(int s) const {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < particles; ++i)
    if (s < 0 || species[i] == s) out.push_back(i);
  return out;
}

namespace {

const std::string kAll = "/particles/all";

void check_times_increase(const std::string& path, const std::vector<double>& time) {
  for (std::size_t f = 1; f < time.size(); ++f) {
    if (!(time[f] > time[f - 1]))
      throw InputError(path, kAll + "/position/time",
                       "frames out of order: frame " + std::to_string(f) + " has time " + std::to_string(time[f]) +
                           " after " + std::to_string(time[f - 1]) + " (times must increase strictly)");
  }
}

/// The frame times of a file, checked (as many as there are frames, strictly increasing).
std::vector<double> checked_frame_times(const io::H5mdReader& r) {
  std::vector<double> time = r.frame_times();
  if (time.size() < r.frame_count()) throw InputError(r.path(), kAll + "/position/time", "fewer time stamps than frames");
  time.resize(r.frame_count());
  check_times_increase(r.path(), time);
  return time;
}

template <class T>
std::vector<T> pick(const std::vector<T>& all, const io::FrameSlice& frames, std::size_t width = 1) {
  std::vector<T> out;
  out.reserve(frames.count * width);
  for (std::size_t k = 0; k < frames.count; ++k)
    for (std::size_t c = 0; c < width; ++c) out.push_back(all[frames.frame(k) * width + c]);
  return out;
}

void unwrap_positions(Trajectory& t, const std::vector<double>& images) {
  for (std::size_t f = 0; f < t.frames; ++f)
    for (std::size_t i = 0; i < t.particles; ++i)
      for (int a = 0; a < 3; ++a) t.position[3 * (f * t.particles + i) + a] += images[3 * (f * t.particles + i) + a] * t.box[3 * f + a];
}

/// Species and ids must not change along a trajectory (the analyses follow particles by index).
void read_identities(Trajectory& t, const io::H5mdReader& r, const io::FrameSlice& frames) {
  const auto species = r.read_integer_element_frames("species", frames);
  const auto ids = r.read_integer_element_frames("id", frames);
  const std::size_t n = t.particles;
  t.species.assign(species.begin(), species.begin() + static_cast<std::ptrdiff_t>(n));
  t.id.assign(ids.begin(), ids.begin() + static_cast<std::ptrdiff_t>(n));
  for (std::size_t f = 1; f < t.frames; ++f)
    for (std::size_t i = 0; i < n; ++i) {
      if (ids[f * n + i] != t.id[i])
        throw InputError(t.path, kAll + "/id/value", "particle order changes at frame " + std::to_string(t.file_frame(f)) + " (the analyses follow particles by index)");
      if (species[f * n + i] != t.species[i])
        throw InputError(t.path, kAll + "/species/value", "particle " + std::to_string(i) + " changes species at frame " + std::to_string(t.file_frame(f)));
    }
}

/// The rows of an observable whose time lies in the window (all rows without one).
ObservableSeries windowed_series(const io::H5mdReader::Series& s, const FrameWindow& w) {
  ObservableSeries out;
  out.width = s.width;
  for (std::size_t r = 0; r < s.rows(); ++r) {
    if (!w.contains(s.time[r])) continue;
    out.time.push_back(s.time[r]);
    out.value.insert(out.value.end(), s.value.begin() + static_cast<std::ptrdiff_t>(r * s.width),
                     s.value.begin() + static_cast<std::ptrdiff_t>((r + 1) * s.width));
  }
  return out;
}

/// An event list in the window: the row in force at the window's start (the last one before it),
/// then the events inside, so that its first row is still the initial state.
ObservableSeries windowed_events(const io::H5mdReader::Series& s, const FrameWindow& w) {
  ObservableSeries out = windowed_series(s, w);
  if (!w.given || !w.from) return out;
  std::size_t before = s.rows();
  for (std::size_t r = 0; r < s.rows() && s.time[r] < *w.from && !w.contains(s.time[r]); ++r) before = r;
  if (before == s.rows()) return out;
  out.time.insert(out.time.begin(), s.time[before]);
  out.value.insert(out.value.begin(), s.value.begin() + static_cast<std::ptrdiff_t>(before * s.width),
                   s.value.begin() + static_cast<std::ptrdiff_t>((before + 1) * s.width));
  return out;
}

void read_observables(Trajectory& t, const io::H5mdReader& r, const TrajectoryNeeds& needs) {
  for (const auto& name : needs.observables)
    if (r.has_observable(name)) t.observables.emplace(name, windowed_series(r.read_observable(name), needs.window));
  for (const auto& name : needs.event_observables)
    if (r.has_observable(name)) t.observables.emplace(name, windowed_events(r.read_observable(name), needs.window));
}

void read_elements(Trajectory& t, const io::H5mdReader& r, const TrajectoryNeeds& needs, const io::FrameSlice& frames) {
  std::size_t width = 0;
  for (const auto& name : needs.elements) {
    auto data = r.read_element_frames(name, width, frames);
    t.elements.emplace(name, std::make_pair(width, std::move(data)));
  }
  const auto present = r.particle_element_names();
  for (const auto& name : needs.optional_elements) {
    if (std::find(present.begin(), present.end(), name) == present.end() || t.elements.count(name)) continue;
    auto data = r.read_element_frames(name, width, frames);
    t.elements.emplace(name, std::make_pair(width, std::move(data)));
  }
}

Trajectory load_frames(const io::H5mdReader& r, const std::vector<double>& all_times, const TrajectoryNeeds& needs,
                       const io::FrameSlice& frames) {
  Trajectory t;
  t.path = r.path();
  t.frames = frames.count;
  t.particles = r.particle_count();
  t.time = pick(all_times, frames);
  t.step = pick(r.frame_steps(), frames);
  for (std::size_t k = 0; k < frames.count; ++k) t.frame_index.push_back(frames.frame(k));
  t.box = pick(r.box_edges_frames(), frames, 3);
  t.species_table = r.species();
  read_identities(t, r, frames);
  t.parameters = r.parameters();
  t.units = tool::unit_system_of_run(t.parameters);
  std::size_t width = 0;
  if (needs.positions) {
    t.position = r.read_element_frames("position", width, frames);
    const auto images = r.read_element_frames("image", width, frames);
    unwrap_positions(t, images);
  }
  if (needs.orientations) {
    t.orientation = r.read_element_frames("orientation", width, frames);
    if (width != 4) throw InputError(t.path, kAll + "/orientation/value", "expected 4 quaternion components");
  }
  read_elements(t, r, needs, frames);
  read_observables(t, r, needs);
  return t;
}

/// The frames of the window on `grid`; fewer than needs.min_frames in a given window → InputError
/// naming the configuration's `window`, the trajectory and what the window selected.
io::FrameSlice window_frames(const TrajectoryNeeds& needs, const std::vector<double>& grid, const std::string& path) {
  if (grid.empty()) throw InputError(path, kAll + "/position/value", "the file holds no frames");
  const io::FrameSlice frames = needs.window.select(grid);
  if (needs.window.given && frames.count < needs.min_frames)
    throw InputError(needs.window.config_file, "window", needs.window.too_few_frames(frames, grid, path, needs.min_frames));
  return frames;
}

}  // namespace

Trajectory load_trajectory(const std::string& path, const TrajectoryNeeds& needs) {
  io::H5mdReader r(path);
  const std::vector<double> time = checked_frame_times(r);
  return load_frames(r, time, needs, window_frames(needs, time, path));
}

Trajectory load_trajectory(const std::string& path, const TrajectoryNeeds& needs, const io::FrameSlice& frames) {
  io::H5mdReader r(path);
  const std::vector<double> time = checked_frame_times(r);
  if (time.empty()) throw InputError(path, kAll + "/position/value", "the file holds no frames");
  return load_frames(r, time, needs, frames);
}

std::vector<std::string> expand_inputs(const std::vector<std::string>& patterns, const std::string& source) {
  std::vector<std::string> out;
  std::set<std::string> seen;
  for (const auto& p : patterns) {
    std::vector<std::string> matches;
    if (p.find_first_of("*?[") != std::string::npos) {
      glob_t g{};
      const int rc = glob(p.c_str(), 0, nullptr, &g);
      if (rc == 0)
        for (std::size_t k = 0; k < g.gl_pathc; ++k) matches.emplace_back(g.gl_pathv[k]);
      globfree(&g);
      if (matches.empty()) throw InputError(source, "", "no input file matches '" + p + "'");
    } else {
      std::error_code ec;
      if (!std::filesystem::exists(p, ec)) throw InputError(p, "", "cannot open file: No such file or directory");
      matches.push_back(p);
    }
    std::sort(matches.begin(), matches.end());
    for (auto& m : matches)
      if (seen.insert(m).second) out.push_back(m);
  }
  if (out.empty()) throw InputError(source, "", "expected at least one input trajectory (--input FILE or a glob, repeatable)");
  return out;
}

namespace {

[[noreturn]] void replica_mismatch(const Trajectory& a, const Trajectory& b, const std::string& what) {
  throw InputError(b.path, "", "mismatched replicas: " + what + " (" + a.path + " vs " + b.path + ")");
}

void check_replica_identity(const Trajectory& a, const Trajectory& b, bool same_frames = true) {
  if (a.particles != b.particles)
    replica_mismatch(a, b, std::to_string(b.particles) + " particles, the first replica has " + std::to_string(a.particles));
  if (a.species != b.species) replica_mismatch(a, b, "the particles' species differ");
  if (a.species_table.size() != b.species_table.size()) replica_mismatch(a, b, "the species tables differ");
  for (std::size_t s = 0; s < a.species_table.size(); ++s)
    if (a.species_table[s].name != b.species_table[s].name) replica_mismatch(a, b, "the species tables differ");
  if (a.units.to_json() != b.units.to_json())
    replica_mismatch(a, b, "the runs' unit systems differ (" + b.units.to_json().dump() + ", the first replica's " + a.units.to_json().dump() + ")");
  if (same_frames && a.frames != b.frames)
    replica_mismatch(a, b, std::to_string(b.frames) + " frames, the first replica has " + std::to_string(a.frames));
}

void check_replica_times(const Trajectory& a, const Trajectory& b, double time_tolerance, const io::FrameSlice& compared) {
  if (compared.count == 0) return;
  // DMC clocks drift apart over a run: the tolerance is relative to the time elapsed up to the
  // last compared frame (the whole run when every frame is compared).
  const double scale = std::max(std::abs(a.time[compared.frame(compared.count - 1)] - a.time.front()), 1e-300);
  for (std::size_t k = 0; k < compared.count; ++k) {
    const std::size_t f = compared.frame(k);
    if (std::abs(a.time[f] - b.time[f]) > time_tolerance * scale)
      replica_mismatch(a, b, "frame " + std::to_string(f) + " is at time " + std::to_string(b.time[f]) + ", the first replica's at " +
                                 std::to_string(a.time[f]) + " (more than " + std::to_string(100 * time_tolerance) + "% of the run apart)");
  }
}

}  // namespace

void check_replica_matches(const Trajectory& a, const Trajectory& b, double time_tolerance, const io::FrameSlice& compared) {
  const bool independent = time_tolerance == kIndependentTimes;
  check_replica_identity(a, b, !independent);
  if (!independent) check_replica_times(a, b, time_tolerance, compared);
}

void check_replica_matches(const Trajectory& a, const Trajectory& b, double time_tolerance) {
  check_replica_matches(a, b, time_tolerance, io::FrameSlice{0, a.frames, 1});
}

namespace {

/// What the replica comparison needs, read cheaply (times and the first frame): mismatched replicas
/// are reported before any replica is analysed.
Trajectory replica_header(const std::string& path) {
  io::H5mdReader r(path);
  Trajectory t;
  t.path = path;
  t.frames = r.frame_count();
  t.particles = r.particle_count();
  t.time = r.frame_times();
  t.time.resize(std::min(t.time.size(), t.frames));
  t.species_table = r.species();
  t.units = tool::unit_system_of_run(r.parameters());
  if (t.frames > 0) {
    const State s = r.read_frame(0);
    t.species.assign(s.particles.species.begin(), s.particles.species.end());
  }
  return t;
}

/// Mean time stamp of each frame over the replicas' headers (all of one length).
std::vector<double> common_grid(const std::vector<Trajectory>& headers) {
  std::vector<double> grid(headers.front().time.size(), 0.0);
  for (const auto& h : headers)
    for (std::size_t f = 0; f < grid.size() && f < h.time.size(); ++f) grid[f] += h.time[f] / static_cast<double>(headers.size());
  return grid;
}

/// Replicas on their own time axes: each one's window frames from its own times.
std::vector<double> for_each_independent_replica(const std::vector<std::string>& paths, const std::vector<Trajectory>& headers,
                                                 const TrajectoryNeeds& needs,
                                                 const std::function<void(const Trajectory&, std::size_t)>& fn,
                                                 FrameSelection* selected) {
  for (std::size_t k = 1; k < headers.size(); ++k) check_replica_identity(headers.front(), headers[k], /*same_frames=*/false);
  for (std::size_t k = 0; k < paths.size(); ++k) {
    const io::FrameSlice frames = window_frames(needs, headers[k].time, paths[k]);
    if (k == 0 && selected) *selected = {frames, headers[k].time};
    fn(load_trajectory(paths[k], needs, frames), k);
  }
  return headers.front().time;
}

}  // namespace

std::vector<double> for_each_replica(const std::vector<std::string>& paths, const TrajectoryNeeds& needs,
                                     const std::function<void(const Trajectory&, std::size_t)>& fn, double time_tolerance,
                                     FrameSelection* selected) {
  std::vector<Trajectory> headers;
  for (const auto& p : paths) headers.push_back(replica_header(p));
  if (time_tolerance == kIndependentTimes) return for_each_independent_replica(paths, headers, needs, fn, selected);
  for (std::size_t k = 1; k < headers.size(); ++k) check_replica_identity(headers.front(), headers[k]);  // the grid needs equal lengths
  const std::vector<double> grid = common_grid(headers);
  const io::FrameSlice frames = window_frames(needs, grid, paths.front());
  for (std::size_t k = 1; k < headers.size(); ++k) check_replica_times(headers.front(), headers[k], time_tolerance, frames);
  if (selected) *selected = {frames, grid};
  for (std::size_t k = 0; k < paths.size(); ++k) fn(load_trajectory(paths[k], needs, frames), k);
  return pick(grid, frames);  // the mean time of each analysed frame over the replicas
}

}  // namespace anisodyn::analysis

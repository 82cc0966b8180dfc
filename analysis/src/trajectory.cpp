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

void check_times_increase(const Trajectory& t) {
  for (std::size_t f = 1; f < t.frames; ++f) {
    if (!(t.time[f] > t.time[f - 1]))
      throw InputError(t.path, kAll + "/position/time",
                       "frames out of order: frame " + std::to_string(f) + " has time " + std::to_string(t.time[f]) +
                           " after " + std::to_string(t.time[f - 1]) + " (times must increase strictly)");
  }
}

void unwrap_positions(Trajectory& t, const std::vector<double>& images) {
  for (std::size_t f = 0; f < t.frames; ++f)
    for (std::size_t i = 0; i < t.particles; ++i)
      for (int a = 0; a < 3; ++a) t.position[3 * (f * t.particles + i) + a] += images[3 * (f * t.particles + i) + a] * t.box[3 * f + a];
}

/// Species and ids must not change along a trajectory (the analyses follow particles by index).
void read_identities(Trajectory& t, const io::H5mdReader& r) {
  const auto species = r.read_integer_element_frames("species");
  const auto ids = r.read_integer_element_frames("id");
  const std::size_t n = t.particles;
  t.species.assign(species.begin(), species.begin() + static_cast<std::ptrdiff_t>(n));
  t.id.assign(ids.begin(), ids.begin() + static_cast<std::ptrdiff_t>(n));
  for (std::size_t f = 1; f < t.frames; ++f)
    for (std::size_t i = 0; i < n; ++i) {
      if (ids[f * n + i] != t.id[i])
        throw InputError(t.path, kAll + "/id/value", "particle order changes at frame " + std::to_string(f) + " (the analyses follow particles by index)");
      if (species[f * n + i] != t.species[i])
        throw InputError(t.path, kAll + "/species/value", "particle " + std::to_string(i) + " changes species at frame " + std::to_string(f));
    }
}

}  // namespace

Trajectory load_trajectory(const std::string& path, const TrajectoryNeeds& needs) {
  io::H5mdReader r(path);
  Trajectory t;
  t.path = path;
  t.frames = r.frame_count();
  t.particles = r.particle_count();
  if (t.frames == 0) throw InputError(path, kAll + "/position/value", "the file holds no frames");
  t.time = r.frame_times();
  t.step = r.frame_steps();
  if (t.time.size() < t.frames) throw InputError(path, kAll + "/position/time", "fewer time stamps than frames");
  t.time.resize(t.frames);
  t.step.resize(t.frames);
  check_times_increase(t);
  t.box = r.box_edges_frames();
  t.species_table = r.species();
  read_identities(t, r);
  t.parameters = r.parameters();
  std::size_t width = 0;
  if (needs.positions) {
    t.position = r.read_element_frames("position", width);
    const auto images = r.read_element_frames("image", width);
    unwrap_positions(t, images);
  }
  if (needs.orientations) {
    t.orientation = r.read_element_frames("orientation", width);
    if (width != 4) throw InputError(path, kAll + "/orientation/value", "expected 4 quaternion components");
  }
  for (const auto& name : needs.elements) {
    auto data = r.read_element_frames(name, width);
    t.elements.emplace(name, std::make_pair(width, std::move(data)));
  }
  const auto present = r.particle_element_names();
  for (const auto& name : needs.optional_elements) {
    if (std::find(present.begin(), present.end(), name) == present.end() || t.elements.count(name)) continue;
    auto data = r.read_element_frames(name, width);
    t.elements.emplace(name, std::make_pair(width, std::move(data)));
  }
  for (const auto& name : needs.observables) {
    if (!r.has_observable(name)) continue;
    const auto s = r.read_observable(name);
    t.observables.emplace(name, ObservableSeries{s.time, s.value, s.width});
  }
  return t;
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

void check_replica_matches(const Trajectory& a, const Trajectory& b, double time_tolerance) {
  const std::string both = " (" + a.path + " vs " + b.path + ")";
  auto mismatch = [&](const std::string& what) { throw InputError(b.path, "", "mismatched replicas: " + what + both); };
  if (a.particles != b.particles)
    mismatch(std::to_string(b.particles) + " particles, the first replica has " + std::to_string(a.particles));
  if (a.species != b.species) mismatch("the particles' species differ");
  if (a.species_table.size() != b.species_table.size()) mismatch("the species tables differ");
  for (std::size_t s = 0; s < a.species_table.size(); ++s)
    if (a.species_table[s].name != b.species_table[s].name) mismatch("the species tables differ");
  if (time_tolerance == kIndependentTimes) return;
  if (a.frames != b.frames) mismatch(std::to_string(b.frames) + " frames, the first replica has " + std::to_string(a.frames));
  const double scale = std::max(std::abs(a.time.back() - a.time.front()), 1e-300);
  for (std::size_t f = 0; f < a.frames; ++f) {
    if (std::abs(a.time[f] - b.time[f]) > time_tolerance * scale)
      mismatch("frame " + std::to_string(f) + " is at time " + std::to_string(b.time[f]) + ", the first replica's at " +
               std::to_string(a.time[f]) + " (more than " + std::to_string(100 * time_tolerance) + "% of the run apart)");
  }
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
  if (t.frames > 0) {
    const State s = r.read_frame(0);
    t.species.assign(s.particles.species.begin(), s.particles.species.end());
  }
  return t;
}

}  // namespace

std::vector<double> for_each_replica(const std::vector<std::string>& paths, const TrajectoryNeeds& needs,
                                     const std::function<void(const Trajectory&, std::size_t)>& fn, double time_tolerance) {
  if (paths.size() > 1) {
    const Trajectory head = replica_header(paths.front());
    for (std::size_t k = 1; k < paths.size(); ++k) check_replica_matches(head, replica_header(paths[k]), time_tolerance);
  }
  std::vector<double> mean_time;
  for (std::size_t k = 0; k < paths.size(); ++k) {
    Trajectory t = load_trajectory(paths[k], needs);
    if (k == 0) mean_time.assign(t.frames, 0.0);
    // (Replicas on independent time axes may differ in length: the mean then covers the common frames.)
    for (std::size_t f = 0; f < std::min(t.frames, mean_time.size()); ++f) mean_time[f] += t.time[f] / static_cast<double>(paths.size());
    fn(t, k);
  }
  return mean_time;
}

}  // namespace anisodyn::analysis

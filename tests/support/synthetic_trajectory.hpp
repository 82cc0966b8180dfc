#pragma once
// Synthetic trajectories with known statistics for the analysis tests, written through the
// engine's H5mdWriter (independent of the analysis code under test). The generator fills unwrapped
// positions and orientations frame by frame; write() wraps them into the box with image counts.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "anisodyn/geometry/shape.hpp"
#include "anisodyn/io/h5md.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn::testing_support {

struct SyntheticTrajectory {
  Vec3 box = Vec3(20, 20, 20);
  std::vector<double> time;
  std::vector<std::vector<Vec3>> position;    // [frame][particle], unwrapped
  std::vector<std::vector<Quat>> orientation; // [frame][particle] (identity if empty)
  std::vector<int> species;                   // [particle] (all 0 if empty)
  SpeciesTable table{Species{"A", Shape::sphere(1.0), 1.0, Vec3::Ones(), Vec3::Ones()}};
  /// Extra per-particle elements: name → [frame][particle × width].
  std::vector<std::pair<std::string, std::pair<std::size_t, std::vector<std::vector<double>>>>> extras;
  /// The run's parameters (/parameters/config), e.g. anisodyn-bd's external_torque.
  nlohmann::json parameters;
  /// Observables: name → rows of (time, values).
  std::vector<std::pair<std::string, std::vector<std::pair<double, std::vector<double>>>>> observables;

  std::size_t particles() const { return position.empty() ? 0 : position.front().size(); }

  void write(const std::string& path) const {
    io::H5mdHeader header;
    header.species = table;
    header.parameters = parameters;
    io::H5mdWriter w(path, header);
    for (std::size_t f = 0; f < time.size(); ++f) {
      State s;
      s.box.set_edges(box);
      s.species = table;
      s.step = static_cast<std::int64_t>(f);
      s.time = time[f];
      for (std::size_t i = 0; i < particles(); ++i) {
        const Vec3& r = position[f][i];
        Vec3 wrapped;
        Int3 image;
        for (int a = 0; a < 3; ++a) {
          const double n = std::floor(r[a] / box[a]);
          image[a] = static_cast<int>(n);
          wrapped[a] = r[a] - n * box[a];
        }
        const Quat q = orientation.empty() ? Quat::Identity() : orientation[f][i];
        s.particles.add(species.empty() ? 0 : species[i], wrapped, q, static_cast<std::int64_t>(i));
        s.particles.set_image(i, image);
      }
      std::vector<io::ParticleElement> extra;
      for (const auto& [name, e] : extras) extra.push_back({name, e.first, e.second[f].data()});
      w.append_frame(s, extra);
    }
    for (const auto& [name, rows] : observables)
      for (std::size_t k = 0; k < rows.size(); ++k)
        w.append_observable(name, static_cast<std::int64_t>(k), rows[k].first, rows[k].second);
    w.commit();
  }
};

/// The frames first, first + stride, … (count of them) of t, as their own trajectory (the
/// truncated run a time window must reproduce); observables are kept whole.
inline SyntheticTrajectory frames_of(const SyntheticTrajectory& t, std::size_t first, std::size_t count, std::size_t stride = 1) {
  SyntheticTrajectory out = t;
  out.time.clear();
  out.position.clear();
  out.orientation.clear();
  for (auto& extra : out.extras) extra.second.second.clear();
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t f = first + k * stride;
    out.time.push_back(t.time[f]);
    out.position.push_back(t.position[f]);
    if (!t.orientation.empty()) out.orientation.push_back(t.orientation[f]);
    for (std::size_t e = 0; e < t.extras.size(); ++e) out.extras[e].second.second.push_back(t.extras[e].second.second[f]);
  }
  return out;
}

/// Frames at t = k·dt, k = 0 … frames − 1.
inline std::vector<double> linear_times(std::size_t frames, double dt) {
  std::vector<double> t(frames);
  for (std::size_t k = 0; k < frames; ++k) t[k] = static_cast<double>(k) * dt;
  return t;
}

/// Independent Gaussian random walks with per-axis diffusion coefficients D (lab frame):
/// each step adds N(0, 2 D_a Δt) along axis a.
inline SyntheticTrajectory gaussian_walks(std::size_t n, const std::vector<double>& time, const Vec3& D, unsigned seed,
                                          const Vec3& box = Vec3(20, 20, 20)) {
  SyntheticTrajectory t;
  t.box = box;
  t.time = time;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  t.position.assign(time.size(), std::vector<Vec3>(n));
  for (std::size_t i = 0; i < n; ++i) t.position[0][i] = Vec3(u(rng) * box.x(), u(rng) * box.y(), u(rng) * box.z());
  for (std::size_t f = 1; f < time.size(); ++f) {
    const double dt = time[f] - time[f - 1];
    for (std::size_t i = 0; i < n; ++i)
      for (int a = 0; a < 3; ++a) t.position[f][i][a] = t.position[f - 1][i][a] + std::sqrt(2 * D[a] * dt) * g(rng);
  }
  return t;
}

}  // namespace anisodyn::testing_support

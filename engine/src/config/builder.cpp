#include "anisodyn/config/builder.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "anisodyn/core/quaternion.hpp"
#include "anisodyn/interactions/hard_overlap.hpp"

namespace anisodyn {

int default_alignment_axis(const Shape& shape) { return shape.alignment_axis(); }

Vec3 box_edges_for_packing_fraction(const SpeciesTable& species, const std::vector<std::size_t>& counts,
                                    double eta, const Vec3& aspect) {
  double v = 0.0;
  for (std::size_t s = 0; s < counts.size(); ++s) v += static_cast<double>(counts[s]) * species[s].shape.volume();
  const double volume = v / eta;
  return aspect * std::cbrt(volume / aspect.prod());
}

namespace {

Quat draw_orientation(const OrientationRule& rule, Rng& rng) {
  if (rule.mode == OrientationRule::Mode::Random) return uniform_quaternion(rng.uniform(), rng.uniform(), rng.uniform());
  Vec3 axis = Vec3::Zero();
  axis[rule.body_axis] = 1.0;
  Quat q = quat_aligning(axis, rule.director.normalized());
  if (rule.random_azimuth) {
    const double phi = 2.0 * M_PI * rng.uniform();
    q = Quat(Eigen::AngleAxisd(phi, rule.director.normalized())) * q;
  }
  return q.normalized();
}

/// New particles in random order (species interleaved), each with its orientation.
std::vector<std::pair<int, Quat>> draw_particles(const PlacementRequest& req, Rng& rng) {
  std::vector<std::pair<int, Quat>> out;
  for (std::size_t s = 0; s < req.counts.size(); ++s)
    for (std::size_t k = 0; k < req.counts[s]; ++k) out.emplace_back(static_cast<int>(s), draw_orientation(req.rules[s], rng));
  for (std::size_t i = out.size(); i > 1; --i) std::swap(out[i - 1], out[rng.index(i)]);
  return out;
}

std::int64_t next_id(const State& state) {
  const auto& ids = state.particles.id;
  return ids.empty() ? 0 : *std::max_element(ids.begin(), ids.end()) + 1;
}

}  // namespace

void place_on_lattice(State& state, const PlacementRequest& req, Rng& rng) {
  const auto particles = draw_particles(req, rng);
  if (particles.empty()) return;
  Vec3 spacing = Vec3::Zero();
  for (const auto& [s, q] : particles)
    spacing = spacing.cwiseMax(2.0 * state.species[static_cast<std::size_t>(s)].shape.lab_half_extents(q.toRotationMatrix()));
  spacing *= 1.0 + 1e-9;  // strict separation: contact counts as overlap
  const Vec3& L = state.box.edges();
  Int3 most;
  for (int k = 0; k < 3; ++k) most[k] = static_cast<int>(std::floor(L[k] / spacing[k]));
  const double capacity = most.cast<double>().prod();
  if (capacity < static_cast<double>(particles.size()))
    throw PlacementFailure("a lattice holds at most " + std::to_string(static_cast<long long>(capacity)) + " of these particles in this box, " +
                           std::to_string(particles.size()) + " requested: lower the packing fraction (and compress with anisodyn-mc) or use random orientations");
  // Fewest sites per axis, in proportion to the room along it, that still hold every particle.
  const double scale = std::cbrt(static_cast<double>(particles.size()) / capacity);
  Int3 n;
  for (int k = 0; k < 3; ++k) n[k] = std::clamp(static_cast<int>(std::ceil(scale * most[k])), 1, most[k]);
  while (n.cast<double>().prod() < static_cast<double>(particles.size())) {
    int grow = -1;
    for (int k = 0; k < 3; ++k)
      if (n[k] < most[k] && (grow < 0 || double(n[k]) / most[k] < double(n[grow]) / most[grow])) grow = k;
    ++n[grow];
  }
  std::vector<int> sites(static_cast<std::size_t>(n.prod()));
  std::iota(sites.begin(), sites.end(), 0);
  for (std::size_t i = sites.size(); i > 1; --i) std::swap(sites[i - 1], sites[rng.index(i)]);
  std::int64_t id = next_id(state);
  for (std::size_t m = 0; m < particles.size(); ++m) {
    const int site = sites[m];
    const Int3 c(site / (n[1] * n[2]), (site / n[2]) % n[1], site % n[2]);
    const Vec3 r = (c.cast<double>() + Vec3::Constant(0.5)).cwiseProduct(L).cwiseQuotient(n.cast<double>());
    state.particles.add(particles[m].first, r, particles[m].second, id++);
  }
}

void place_uniformly(State& state, const PlacementRequest& req, Rng& rng) {
  std::int64_t id = next_id(state);
  const Vec3& L = state.box.edges();
  for (const auto& [s, q] : draw_particles(req, rng))
    state.particles.add(s, Vec3(rng.uniform() * L.x(), rng.uniform() * L.y(), rng.uniform() * L.z()), q, id++);
}

void place_at_centre(State& state, const PlacementRequest& req, Rng& rng) {
  const auto particles = draw_particles(req, rng);
  if (particles.size() != 1 || state.particles.size() != 0)
    throw PlacementFailure("the centre holds exactly one particle; " + std::to_string(particles.size() + state.particles.size()) + " requested");
  state.particles.add(particles.front().first, 0.5 * state.box.edges(), particles.front().second, next_id(state));
}

void insert_randomly(State& state, const PlacementRequest& req, Rng& rng) {
  const auto particles = draw_particles(req, rng);
  // Largest first: small particles fill the gaps afterwards. (Indices are sorted, not the pairs:
  // std::stable_sort's scratch buffer does not honour Eigen's quaternion alignment.)
  std::vector<std::size_t> order(particles.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  auto volume = [&](std::size_t k) { return state.species[static_cast<std::size_t>(particles[k].first)].shape.volume(); };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return volume(a) > volume(b); });
  std::vector<std::size_t> expected(state.species.size(), 0);
  for (auto s : state.particles.species) expected[static_cast<std::size_t>(s)]++;
  for (std::size_t s = 0; s < req.counts.size(); ++s) expected[s] += req.counts[s];
  HardOverlap overlap(state, expected);
  std::int64_t id = next_id(state);
  const Vec3& L = state.box.edges();
  for (std::size_t m = 0; m < particles.size(); ++m) {
    const auto& [s, q] = particles[order[m]];
    const Mat3 rot = q.toRotationMatrix();
    const std::int32_t i = static_cast<std::int32_t>(state.particles.size());
    bool placed = false;
    for (std::size_t attempt = 0; attempt < req.max_attempts_per_particle && !placed; ++attempt) {
      const Vec3 r(rng.uniform() * L.x(), rng.uniform() * L.y(), rng.uniform() * L.z());
      state.particles.add(s, r, q, id);
      if (overlap.overlaps(i, r, rot)) {
        state.particles.pop_back();
        continue;
      }
      overlap.inserted(i);
      placed = true;
    }
    if (!placed)
      throw PlacementFailure("random insertion stuck: placed " + std::to_string(m) + " of " + std::to_string(particles.size()) +
                             " particles (packing fraction reached " + std::to_string(state.packing_fraction()) + ") after " +
                             std::to_string(req.max_attempts_per_particle) +
                             " attempts for the next one; use placement \"lattice\" at low density and compress with anisodyn-mc");
    ++id;
  }
}

bool inside_body(const State& state, std::size_t i, const Vec3& r) {
  const Particles& p = state.particles;
  const Shape& shape = state.species[static_cast<std::size_t>(p.species[i])].shape;
  const Vec3 d = state.box.min_image(r - p.position(i));
  switch (shape.kind) {
    case ShapeKind::Sphere: return d.norm() < 0.5 * shape.diameter;
    case ShapeKind::Spherocylinder: {
      // Distance from the axis segment (body z, ±length/2) below the radius.
      const Vec3 axis = p.orientation(i) * Vec3::UnitZ();
      const double along = std::clamp(d.dot(axis), -0.5 * shape.length, 0.5 * shape.length);
      return (d - along * axis).norm() < 0.5 * shape.diameter;
    }
    default:
      throw InputError(std::string("a liquid can be placed around spheres and spherocylinders, not a ") + shape_kind_name(shape.kind));
  }
}

void fill_liquid(State& state, int liquid, std::size_t count, Rng& rng, double z_min, double z_max, std::size_t max_attempts) {
  const std::size_t bodies = state.particles.size();
  std::int64_t id = next_id(state);
  const Vec3& L = state.box.edges();
  for (std::size_t k = 0; k < count; ++k) {
    std::size_t attempt = 0;
    for (;; ++attempt) {
      if (attempt == max_attempts)
        throw PlacementFailure("no room for liquid particle " + std::to_string(k) + " after " + std::to_string(max_attempts) + " draws");
      const Vec3 r(rng.uniform() * L.x(), rng.uniform() * L.y(), z_min + rng.uniform() * (z_max - z_min));
      bool free = true;
      for (std::size_t i = 0; i < bodies && free; ++i) free = !inside_body(state, i, r);
      if (!free) continue;
      state.particles.add(liquid, r, Quat::Identity(), id++);
      break;
    }
  }
}

}  // namespace anisodyn

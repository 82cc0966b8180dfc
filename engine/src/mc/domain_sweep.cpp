#include "anisodyn/mc/domain_sweep.hpp"

#include <algorithm>
#include <cmath>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace anisodyn {

namespace {

/// Stream of the slab generators (their seeds come from the engine's generator).
constexpr std::uint64_t kSlabStream = 0x736c6162;  // "slab"

int slab_threads() {
#ifdef _OPENMP
  return std::min(DomainSweep::kSlabs, omp_get_max_threads());
#else
  return 1;
#endif
}

template <class Parts>
int first_active(const Parts& parts) {
  for (std::size_t k = 0; k < parts.size(); ++k)
    if (!parts[k].movable.empty()) return static_cast<int>(k);
  return -1;
}

}  // namespace

void DomainSweep::cycle(State& state, Rng& rng, const MoveSizes& moves, const OrientationalField& field, bool removing_overlaps,
                        MoveCounters& counters) {
  const Particles& p = state.particles;
  const std::size_t n = p.size();
  const int axis = static_cast<int>(rng.index(3));
  const double L = state.box.edges()[axis];
  const double start = rng.uniform() * L;
  std::array<std::uint64_t, kSlabs> seeds{};
  for (auto& s : seeds) s = rng.bits();

  half_extent_.resize(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i)
    half_extent_[i] = state.species[static_cast<std::size_t>(p.species[i])].shape.lab_half_extents(p.orientation(i).toRotationMatrix())[axis];

  for (int k = 0; k < kSlabs; ++k) parts_[static_cast<std::size_t>(k)].slab = Slab{axis, start + k * L / kSlabs, L / kSlabs};
#pragma omp parallel for num_threads(slab_threads()) schedule(static, 1)
  for (int k = 0; k < kSlabs; ++k) gather(state, parts_[static_cast<std::size_t>(k)]);

  // The N trials are shared equally between the slabs that have movable bodies, so the threads
  // finish together; the share does not depend on the configuration beyond which slabs can move,
  // which no trial changes.
  std::int64_t active = 0;
  for (const Part& part : parts_) active += part.movable.empty() ? 0 : 1;
  if (active == 0) return;  // every particle straddles a cut: nothing moves this cycle
  const auto share = static_cast<std::int64_t>(n) / active, extra = static_cast<std::int64_t>(n) % active;
  const int first = first_active(parts_);
#pragma omp parallel for num_threads(slab_threads()) schedule(static, 1)
  for (int k = 0; k < kSlabs; ++k) {
    Part& part = parts_[static_cast<std::size_t>(k)];
    if (part.movable.empty()) continue;  // nothing to move: no copy to index
    sweep(state, part, seeds[static_cast<std::size_t>(k)], share + (k == first ? extra : 0), moves, field, removing_overlaps);
  }
  for (const Part& part : parts_) counters.add_particle_moves(part.counters);
}

void DomainSweep::gather(const State& state, Part& part) const {
  const Particles& p = state.particles;
  const double L = state.box.edges()[part.slab.axis];
  // Movable: strictly inside the slab, by a margin far above round-off, so that movable bodies of
  // different slabs are always apart. Copied: every body that reaches into the slab (a superset
  // of those a movable body can touch).
  const double margin = 1e-9 * L;
  part.inner = Slab{part.slab.axis, part.slab.start + margin, part.slab.width - 2.0 * margin};
  const Slab& inner = part.inner;
  const Slab outer{part.slab.axis, part.slab.start - margin, part.slab.width + 2.0 * margin};
  if (part.sub.species.size() != state.species.size()) part.sub.species = state.species;
  part.sub.box = state.box;
  part.movable.clear();
  const std::vector<double>& coord = part.slab.axis == 0 ? p.x : part.slab.axis == 1 ? p.y : p.z;
  // First the bodies that reach into the slab, without a branch: every index is written and
  // kept when it reaches (about half do, in no predictable order).
  part.global.resize(p.size());
  std::size_t count = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    part.global[count] = static_cast<std::int32_t>(i);
    count += outer.reaches(coord[i], half_extent_[i], L) ? 1 : 0;
  }
  part.global.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    const auto i = static_cast<std::size_t>(part.global[k]);
    if (inner.holds(coord[i], half_extent_[i], L)) part.movable.push_back(static_cast<std::int32_t>(k));
  }
  part.sub.particles.assign_subset(p, part.global);
  part.counters.reset(state.species.size());
}

void DomainSweep::sweep(State& state, Part& part, std::uint64_t seed, std::int64_t trials, const MoveSizes& moves,
                        const OrientationalField& field, bool removing_overlaps) {
  if (part.overlap) part.overlap->rebuild(part.sub);
  else part.overlap.emplace(part.sub);
  Rng rng(seed, kSlabStream);
  // Moves must keep a body movable by the same test that chose it: a move and its reverse then
  // see the same movable set.
  const TrialMove move{part.sub, *part.overlap, rng, part.counters, moves, field, removing_overlaps, &part.inner};
  const std::uint64_t n = part.movable.size();
  for (std::int64_t t = 0; t < trials; ++t) move.attempt(part.movable[rng.index(n)]);
  // Only movable particles changed; they belong to this slab alone.
  Particles& to = state.particles;
  const Particles& from = part.sub.particles;
  for (const std::int32_t s : part.movable) {
    const auto us = static_cast<std::size_t>(s);
    const auto g = static_cast<std::size_t>(part.global[us]);
    to.set_position(g, from.position(us));
    to.set_image(g, from.image(us));
    to.set_orientation(g, from.orientation(us));
  }
}

std::array<std::size_t, DomainSweep::kSlabs> DomainSweep::last_movable() const {
  std::array<std::size_t, kSlabs> m{};
  for (int k = 0; k < kSlabs; ++k) m[static_cast<std::size_t>(k)] = parts_[static_cast<std::size_t>(k)].movable.size();
  return m;
}

}  // namespace anisodyn

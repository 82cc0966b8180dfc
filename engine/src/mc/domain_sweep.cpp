#include "anisodyn/mc/domain_sweep.hpp"

#include <algorithm>
#include <cmath>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "anisodyn/system/lab_extents.hpp"

namespace anisodyn {

namespace {

/// Stream of the domain generators (their seeds come from the engine's generator).
constexpr std::uint64_t kSlabStream = 0x736c6162;  // "slab"
/// The automatic grid keeps every domain at least this many mean lab extents wide along a cut
/// axis: then at most about a third of the particles straddle each cut.
constexpr double kMinEdgeInExtents = 3.0;

int domain_threads(std::size_t domains) {
#ifdef _OPENMP
  return static_cast<int>(std::min<std::size_t>(domains, static_cast<std::size_t>(omp_get_max_threads())));
#else
  (void)domains;
  return 1;
#endif
}

template <class Parts>
int first_active(const Parts& parts) {
  for (std::size_t k = 0; k < parts.size(); ++k)
    if (!parts[k].movable.empty()) return static_cast<int>(k);
  return -1;
}

int domain_count(const DomainSweep::Layout& count) { return count[0] * count[1] * count[2]; }

}  // namespace

std::optional<DomainSweep::Layout> DomainSweep::automatic_layout(const State& state) {
  const Particles& p = state.particles;
  if (p.size() < kGridFrom) return std::nullopt;
  const std::size_t wanted = p.size() / kParticlesPerDomain;
  // The mean lab extent over all particles: the species' means weighted by their counts.
  const std::vector<Vec3> species_half = mean_lab_half_extents(state);
  Vec3 extent = Vec3::Zero();
  for (std::size_t i = 0; i < p.size(); ++i) extent += 2.0 * species_half[static_cast<std::size_t>(p.species[i])];
  extent /= static_cast<double>(p.size());
  const Vec3& L = state.box.edges();
  Layout count{1, 1, 1};
  while (static_cast<std::size_t>(domain_count(count)) < wanted) {
    // The axis whose domains, one more along it, stay widest in units of the mean extent.
    int best = -1;
    double widest = kMinEdgeInExtents;
    for (int k = 0; k < 3; ++k) {
      const double width = L[k] / (count[static_cast<std::size_t>(k)] + 1) / extent[k];
      if (width >= widest) {
        widest = width;
        best = k;
      }
    }
    if (best < 0) break;
    ++count[static_cast<std::size_t>(best)];
  }
  if (domain_count(count) < 2) return std::nullopt;
  return count;
}

void DomainSweep::set_layout(const std::optional<Layout>& grid) {
  grid_ = grid;
  layout_chosen_ = true;
}

DomainSweep::Cut DomainSweep::draw_cut(Rng& rng) const {
  Cut cut;
  if (!grid_) {
    const auto axis = static_cast<std::size_t>(rng.index(3));
    cut.count[axis] = 2;
    cut.offset[static_cast<int>(axis)] = rng.uniform();
    return cut;
  }
  cut.count = *grid_;
  for (int k = 0; k < 3; ++k)
    if (cut.count[static_cast<std::size_t>(k)] > 1) cut.offset[k] = rng.uniform();
  return cut;
}

void DomainSweep::cycle(State& state, Rng& rng, const MoveSizes& moves, const OrientationalField& field, bool removing_overlaps,
                        MoveCounters& counters) {
  cycles(state, rng, 1, moves, field, removing_overlaps, counters);
}

int DomainSweep::cycles(State& state, Rng& rng, int wanted, const MoveSizes& moves, const OrientationalField& field,
                        bool removing_overlaps, MoveCounters& counters) {
  const std::size_t n = state.particles.size();
  if (!layout_chosen_) set_layout(automatic_layout(state));
  if (!cut_) {
    cut_ = draw_cut(rng);
    copies_valid_ = false;
  }
  const int k_cycles = std::clamp(wanted, 1, kCyclesPerCut - cut_->cycles_done);
  // The seeds in the order single cycles draw them: cycle by cycle, domain by domain.
  const std::size_t domain_total = static_cast<std::size_t>(domain_count(cut_->count));
  seeds_.resize(domain_total * static_cast<std::size_t>(k_cycles));
  for (auto& s : seeds_) s = rng.bits();
  if (!copies_valid_ || copied_edges_ != state.box.edges()) copy_domains(state);
  cut_->cycles_done += k_cycles;
  if (cut_->cycles_done == kCyclesPerCut) cut_.reset();

  // The N trials of a cycle are shared equally between the domains that have movable bodies, so
  // the threads finish together; the share does not depend on the configuration beyond which
  // domains can move, which no trial changes. The domains are independent within a cut, so each
  // runs its cycles back to back (its copy stays in cache) with the bits of cycles run one by one.
  std::int64_t active = 0;
  for (const Part& part : parts_) active += part.movable.empty() ? 0 : 1;
  for (Part& part : parts_) part.counters.reset(state.species.size());
  if (active == 0) return k_cycles;  // every particle straddles a cut: nothing moves
  const auto share = static_cast<std::int64_t>(n) / active, extra = static_cast<std::int64_t>(n) % active;
  const int first = first_active(parts_);
  const int domains = static_cast<int>(parts_.size());
#pragma omp parallel for num_threads(domain_threads(parts_.size())) schedule(static)
  for (int k = 0; k < domains; ++k) {
    Part& part = parts_[static_cast<std::size_t>(k)];
    if (part.movable.empty()) continue;  // nothing to move: no copy to index
    const std::int64_t trials = share + (k == first ? extra : 0);
    for (int c = 0; c < k_cycles; ++c)
      sweep(part, seeds_[static_cast<std::size_t>(c) * domain_total + static_cast<std::size_t>(k)], trials, moves, field, removing_overlaps);
    write_back(state, part);
  }
  for (const Part& part : parts_) counters.add_particle_moves(part.counters);
  return k_cycles;
}

void DomainSweep::restore_cut(const std::optional<Cut>& cut) {
  cut_ = cut;
  copies_valid_ = false;
}

void DomainSweep::copy_domains(const State& state) {
  const Particles& p = state.particles;
  const std::size_t n = p.size();
  const Vec3& L = state.box.edges();
  half_extent_.resize(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i)
    half_extent_[i] = state.species[static_cast<std::size_t>(p.species[i])].shape.lab_half_extents(p.orientation(i).toRotationMatrix());

  const Layout& count = cut_->count;
  parts_.resize(static_cast<std::size_t>(domain_count(count)));
  for (std::size_t d = 0; d < parts_.size(); ++d) {
    Domain& domain = parts_[d].domain;
    std::size_t rest = d;
    for (int k = 0; k < 3; ++k) {
      const auto m = static_cast<std::size_t>(count[static_cast<std::size_t>(k)]);
      const double width = L[k] / static_cast<double>(m);
      domain.cut[static_cast<std::size_t>(k)] = m > 1;
      domain.along[static_cast<std::size_t>(k)] = Slab{k, cut_->offset[k] * L[k] + static_cast<double>(rest % m) * width, width};
      rest /= m;
    }
    set_bounds(parts_[d], L);
  }
  bin_particles(state);
  const int domains = static_cast<int>(parts_.size());
#pragma omp parallel for num_threads(domain_threads(parts_.size())) schedule(static)
  for (int k = 0; k < domains; ++k) {
    Part& part = parts_[static_cast<std::size_t>(k)];
    copy_part(state, part);
    if (part.movable.empty()) continue;  // never swept: no search to build
    if (part.overlap) part.overlap->rebuild(part.sub);
    else part.overlap.emplace(part.sub);
  }
  copies_valid_ = true;
  copied_edges_ = L;
}

void DomainSweep::set_bounds(Part& part, const Vec3& L) {
  // Movable: strictly inside the domain, by a margin far above round-off, so that movable bodies
  // of different domains are always apart. Copied: every body that reaches into the domain (a
  // superset of those a movable body can touch).
  part.inner = part.outer = part.domain;
  for (std::size_t k = 0; k < 3; ++k) {
    const double margin = 1e-9 * L[static_cast<int>(k)];
    part.inner.along[k].start += margin;
    part.inner.along[k].width -= 2.0 * margin;
    part.outer.along[k].start -= margin;
    part.outer.along[k].width += 2.0 * margin;
  }
}

void DomainSweep::bin_particles(const State& state) {
  // One pass over the particles: each is listed, in index order, by the few domains its lab box
  // reaches (found per axis from its position, confirmed by the domains' own test).
  const Particles& p = state.particles;
  const Vec3& L = state.box.edges();
  const Layout& count = cut_->count;
  for (Part& part : parts_) part.global.clear();
  std::array<std::vector<int>, 3> reached;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3 c(p.x[i], p.y[i], p.z[i]);
    for (int k = 0; k < 3; ++k) reached_along(k, c[k], half_extent_[i][k], L[k], reached[static_cast<std::size_t>(k)]);
    for (const int a : reached[0])
      for (const int b : reached[1])
        for (const int e : reached[2])
          parts_[static_cast<std::size_t>(a + count[0] * (b + count[1] * e))].global.push_back(static_cast<std::int32_t>(i));
  }
}

void DomainSweep::reached_along(int axis, double c, double h, double L, std::vector<int>& out) const {
  out.clear();
  const auto ua = static_cast<std::size_t>(axis);
  const Layout& count = cut_->count;
  const int m = count[ua];
  if (m == 1) {
    out.push_back(0);
    return;
  }
  // Domain j along the axis starts at the first domain's start plus j widths; the interval's ends,
  // measured from there, bound the indices it can meet (one more on each side covers round-off).
  const Part& first = parts_.front();
  const double start = first.domain.along[ua].start, width = L / m;
  double u = c - start;
  u -= L * std::floor(u / L);
  const auto lo = static_cast<int>(std::floor((u - h) / width)) - 1, hi = static_cast<int>(std::floor((u + h) / width)) + 1;
  const int stride = ua == 0 ? 1 : ua == 1 ? count[0] : count[0] * count[1];
  const int from = hi - lo + 1 >= m ? 0 : lo, to = hi - lo + 1 >= m ? m - 1 : hi;
  for (int t = from; t <= to; ++t) {
    const int j = ((t % m) + m) % m;
    if (parts_[static_cast<std::size_t>(j * stride)].outer.along[ua].reaches(c, h, L)) out.push_back(j);
  }
}

void DomainSweep::copy_part(const State& state, Part& part) const {
  const Particles& p = state.particles;
  const Vec3& L = state.box.edges();
  if (part.sub.species.size() != state.species.size()) part.sub.species = state.species;
  part.sub.box = state.box;
  part.movable.clear();
  for (std::size_t k = 0; k < part.global.size(); ++k) {
    const auto i = static_cast<std::size_t>(part.global[k]);
    if (part.inner.holds(Vec3(p.x[i], p.y[i], p.z[i]), half_extent_[i], L)) part.movable.push_back(static_cast<std::int32_t>(k));
  }
  part.sub.particles.assign_subset(p, part.global);
}

void DomainSweep::sweep(Part& part, std::uint64_t seed, std::int64_t trials, const MoveSizes& moves,
                        const OrientationalField& field, bool removing_overlaps) {
  Rng rng(seed, kSlabStream);
  // Moves must keep a body movable by the same test that chose it: a move and its reverse then
  // see the same movable set.
  const TrialMove move{part.sub, *part.overlap, rng, part.counters, moves, field, removing_overlaps, &part.inner};
  const std::uint64_t n = part.movable.size();
  for (std::int64_t t = 0; t < trials; ++t) move.attempt(part.movable[rng.index(n)]);
}

void DomainSweep::write_back(State& state, const Part& part) {
  // Only movable particles changed; they belong to this domain alone.
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

}  // namespace anisodyn

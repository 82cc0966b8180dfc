#pragma once
// Verlet neighbour lists with a skin, for pair forces (interactions/pair_forces.hpp).
//
// Every particle lists all its partners (a "full" list, each pair twice), sorted by index: a force
// loop can let each particle sum its own pairs in a fixed order, so forces do not depend on the
// thread count and need no atomics. The partners above i (partners_above) are every pair once, and
// pair_slots numbers the pairs, so that a loop can evaluate each pair once and let both particles
// gather its terms, again in a fixed order.
//
// Particles as segments. A species may give its particles a half-length h: particle i is then the
// segment S_i = {r_i + t û_i : |t| ≤ h}, û_i its body z axis (a point when h = 0, the default), and
// the cut-offs are distances between segments. This is for long rods (BD overlap volume, spec 20
// §4.4), whose centre-distance range L + D admits hundreds of partners of which a handful come
// within D: the list keeps the pairs whose segments were closer than cutoff(a, b) + skin when it
// was built.
//
// When the list is stale. A point r + tû of S_i moves by Δr + tΔû since the build, so by at most
//   m_i = |Δr_i| + h |Δû_i|.
// The segment distance d_ij cannot shrink by more than m_i + m_j: at the current closest points,
// with parameters t_i, t_j, the points of the same parameters at the build were at least d_ij(build)
// apart, and each has moved by at most its m. So while m_i ≤ skin/2 for every particle, a pair now
// closer than its cut-off was closer than cut-off + skin at the build, i.e. it is listed. update()
// rebuilds as soon as some m_i > skin/2 (or the box changed). For points (h = 0) m_i = |Δr_i|, the
// usual centre-displacement rule.
//
// Building. Lists of points come from the species cell grids. Lists with segments are pruned from
// a list of candidates: a list of points (this class, h = 0) with the cut-offs
// cutoff(a, b) + h_a + h_b + skin (the centre distance is at most the segment distance + h_a + h_b)
// and twice the skin, kept up to date by its own centre-displacement rule. The segments move much
// more at their ends than at their centres, so the candidates are searched rarely (the cell grids
// see hundreds of rods within reach of a rod), and the segment list is rebuilt from them by the
// exact segment distance (geometry/spherocylinder.hpp) after a test on the distance of the infinite
// axes that rejects most candidates cheaply.
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "anisodyn/core/box.hpp"
#include "anisodyn/core/types.hpp"
#include "anisodyn/system/particles.hpp"

namespace anisodyn {

class VerletList {
 public:
  /// cutoffs[a·nspecies + b]: the pair cut-off of species a and b (symmetric), a distance between
  /// segments; skin > 0; half_lengths[s]: the segment half-length h of species s (empty: all 0,
  /// points, and the cut-offs are centre distances).
  VerletList(std::vector<double> cutoffs, int nspecies, double skin, std::vector<double> half_lengths = {});
  VerletList(VerletList&&) noexcept;
  VerletList& operator=(VerletList&&) noexcept;
  ~VerletList();

  /// Rebuilds when no list exists, the box changed or a particle's segment moved more than skin/2
  /// since the last build (m_i above; positions wrapped into the box). Returns whether it rebuilt.
  bool update(const Box& box, const Particles& p);
  void build(const Box& box, const Particles& p);

  /// Partners of particle i, ascending.
  std::span<const std::int32_t> partners(std::size_t i) const {
    return {partners_.data() + offsets_[i], partners_.data() + offsets_[i + 1]};
  }
  /// Partners of particle i above i, ascending: every listed pair once.
  std::span<const std::int32_t> partners_above(std::size_t i) const {
    return {partners_.data() + above_[i], partners_.data() + offsets_[i + 1]};
  }
  /// For each entry of partners(i), the number of its pair in 0 … pairs() − 1. Pairs are numbered
  /// in the order of partners_above(0), partners_above(1), …
  std::span<const std::int32_t> pair_slots(std::size_t i) const {
    return {pair_slots_.data() + offsets_[i], pair_slots_.data() + offsets_[i + 1]};
  }
  /// Number of the pair of i and its first partner above i; the pairs of partners_above(i) follow it.
  std::size_t first_pair_above(std::size_t i) const { return first_pair_[i]; }
  /// Listed pairs (each once).
  std::size_t pairs() const { return partners_.size() / 2; }

  double cutoff(int a, int b) const { return cutoffs_[static_cast<std::size_t>(a * nspecies_ + b)]; }
  double half_length(int s) const { return half_lengths_[static_cast<std::size_t>(s)]; }
  double skin() const { return skin_; }
  std::int64_t builds() const { return builds_; }
  /// The centre-distance candidates of a list with segments (null for a list of points).
  const VerletList* candidates() const { return candidates_.get(); }

 private:
  void build_from_cells(const Box& box, const Particles& p, std::vector<std::int32_t>& upper, std::vector<std::size_t>& upper_end) const;
  void build_from_candidates(const Box& box, const Particles& p, std::vector<std::int32_t>& upper,
                             std::vector<std::size_t>& upper_end);

  std::vector<double> cutoffs_;
  int nspecies_;
  double skin_;
  std::vector<double> half_lengths_;
  std::unique_ptr<VerletList> candidates_;  // lists with segments only
  Box box_;
  std::vector<Vec3> built_at_, axis_at_;  // axes only for lists with segments
  std::vector<std::size_t> offsets_, above_, first_pair_;
  std::vector<std::int32_t> partners_, pair_slots_;
  std::int64_t builds_ = 0;
};

}  // namespace anisodyn

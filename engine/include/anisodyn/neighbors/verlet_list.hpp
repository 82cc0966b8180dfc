#pragma once
// Verlet neighbour lists with a skin, for pair forces (interactions/pair_forces.hpp).
//
// Every particle lists all its partners (a "full" list, each pair twice), sorted by index: the
// force loop then lets each particle sum its own pairs in a fixed order, so forces do not depend
// on the thread count and need no atomics. Partners are those within cutoff(a, b) + skin when the
// list was built; the list stays valid until some particle has moved more than skin/2 since then
// (or the box changes), and update() rebuilds it when needed. Built on the species cell grids.
#include <cstdint>
#include <span>
#include <vector>

#include "anisodyn/core/box.hpp"
#include "anisodyn/core/types.hpp"
#include "anisodyn/system/particles.hpp"

namespace anisodyn {

class VerletList {
 public:
  /// cutoffs[a·nspecies + b]: the pair cut-off of species a and b (symmetric); skin > 0.
  VerletList(std::vector<double> cutoffs, int nspecies, double skin);

  /// Rebuilds when no list exists, the box changed or a particle moved more than skin/2 since the
  /// last build (positions wrapped into the box). Returns whether it rebuilt.
  bool update(const Box& box, const Particles& p);
  void build(const Box& box, const Particles& p);

  /// Partners of particle i, ascending.
  std::span<const std::int32_t> partners(std::size_t i) const {
    return {partners_.data() + offsets_[i], partners_.data() + offsets_[i + 1]};
  }
  double cutoff(int a, int b) const { return cutoffs_[static_cast<std::size_t>(a * nspecies_ + b)]; }
  double skin() const { return skin_; }
  std::int64_t builds() const { return builds_; }

 private:
  std::vector<double> cutoffs_;
  int nspecies_;
  double skin_;
  Box box_;
  std::vector<Vec3> built_at_;
  std::vector<std::size_t> offsets_;
  std::vector<std::int32_t> partners_;
  std::int64_t builds_ = 0;
};

}  // namespace anisodyn

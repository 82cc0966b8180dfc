#pragma once
// Two-thread sweeps for MC preparation (issue 18): a domain (checkerboard) decomposition. Each
// cycle cuts the box along a random axis at a random offset into two slabs of half its edge. In each
// slab, the particles whose lab extent lies inside it take trial moves that keep them inside; all
// other particles stay put. Bodies inside different slabs cannot touch, so the two slabs are swept
// independently, one per thread, each against its own copy of the particles that reach into it.
//
// Why this samples the hard-particle distribution: the cut (axis, offset) does not depend on the
// configuration; within a slab, picking one of its n movable particles and a move that keeps it
// inside is symmetric (a move and its reverse see the same n), so every trial obeys detailed
// balance; and the number of trials per slab (N shared equally between the slabs that have
// movable bodies: balanced threads) is unchanged by the trials.
// Random cuts let every particle move. Not for DMC, whose dynamics needs the sequential choice.
//
// The slab count is fixed and each slab draws from its own stream, seeded from the engine's
// generator: the result is the same bits on one thread or two.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "anisodyn/mc/trial_move.hpp"

namespace anisodyn {

class DomainSweep {
 public:
  static constexpr int kSlabs = 2;

  /// One cycle on `state`: N trial moves, shared equally between the slabs that have movable
  /// particles. Draws the cut and the slab seeds from `rng`; adds to `counters`.
  void cycle(State& state, Rng& rng, const MoveSizes& moves, const OrientationalField& field, bool removing_overlaps,
             MoveCounters& counters);

  /// Movable particles of the last cycle, per slab (for tests and progress).
  std::array<std::size_t, kSlabs> last_movable() const;

 private:
  /// A slab's own copy of the particles that reach into it.
  struct Part {
    Slab slab;   // the cut
    Slab inner;  // the cut less a margin far above round-off: where movable bodies stay
    State sub;
    std::optional<HardOverlap> overlap;
    std::vector<std::int32_t> global;   // sub index → index in the full state
    std::vector<std::int32_t> movable;  // sub indices of the particles inside the slab
    MoveCounters counters;
  };
  void gather(const State& state, Part& part) const;
  void sweep(State& state, Part& part, std::uint64_t seed, std::int64_t trials, const MoveSizes& moves,
             const OrientationalField& field, bool removing_overlaps);

  std::array<Part, kSlabs> parts_;
  std::vector<double> half_extent_;  // per particle: lab half-extent along the cut axis
};

}  // namespace anisodyn

#pragma once
// Domain (checkerboard) sweeps for MC preparation on several threads (issue 18). A cut divides the
// box into domains and serves kCyclesPerCut cycles: below kGridFrom particles, two
// slabs of half the box edge along a random axis at a random offset; above, a grid of domains per
// axis fixed for the run (automatic_layout) at random offsets. In each domain, the particles whose
// lab extent lies inside it take trial moves that keep them inside; all other particles stay put.
// Bodies inside different domains cannot touch, so the domains are swept independently, on as
// many threads as there are, each against its own copy of the particles that reach into it.
//
// Why this samples the hard-particle distribution: the cuts, and when they change, do not depend on
// the configuration; within a domain, picking one of its n movable particles and a move that keeps
// it inside is symmetric (a move and its reverse see the same n), so every trial obeys detailed
// balance; and the number of trials per slab (N shared equally between the slabs that have
// movable bodies: balanced threads) is unchanged by the trials. Under NPT the engine makes the
// cut's volume moves (one per cycle) on the whole configuration when the cut ends (McEngine); a
// box changed within a cut (quick compression, the squeeze) makes the slabs copy anew.
// Random cuts let every particle move. Not for DMC, whose dynamics needs the sequential choice.
//
// Why a cut serves several cycles: copying the slabs and building their trees costs about as much
// as a tenth of the cycle's trials on dense rods (docs/performance.md), which kept two threads
// below 1.8× the sequential sweep; kept for kCyclesPerCut cycles, the copies and trees are made
// once per cut (and after a volume move), and the slabs' own trees are refitted and rebuilt as the
// sequential sweep's are. The cost: a body that straddles the cut waits kCyclesPerCut cycles.
//
// Why a grid for large systems: a trial of the sequential sweep finds its particle, tree path and
// partners cold once the configuration outgrows the core's cache (32000 rods: 0.4 of the speed at
// 2000). A domain's copy of about kParticlesPerDomain particles and its trees stay in cache while
// its trials run. Run one cycle at a time, each domain's copy was cold again at its turn, 15–20%
// below the speed of 2000 rods in two slabs; cycles() runs each domain's cycles of a cut back to
// back, which removes that step (docs/performance.md).
//
// The domain count is fixed by the cut and each domain draws from its own stream, seeded every
// cycle from the engine's generator: the result is the same bits on any thread count.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "anisodyn/mc/trial_move.hpp"

namespace anisodyn {

class DomainSweep {
 public:
  static constexpr int kCyclesPerCut = 8;
  /// Particles per domain the automatic grid aims at: a copy this size and its trees (an estimated
  /// 0.3 MB for rods) fit a core's L2 cache. 250 was no faster on 54000 rods and freezes more
  /// straddling particles per cut.
  static constexpr std::size_t kParticlesPerDomain = 1000;
  /// Below this many particles, two slabs along a random axis per cut.
  static constexpr std::size_t kGridFrom = 4000;
  /// Domains per axis (1: the axis is not cut).
  using Layout = std::array<int, 3>;

  /// The cut in use: domains per axis, each cut axis's offset as a fraction of the box edge (a
  /// volume move moves it with the particles), and how many of its cycles are done
  /// (< kCyclesPerCut).
  struct Cut {
    Layout count{1, 1, 1};
    Vec3 offset = Vec3::Zero();
    int cycles_done = 0;
  };

  /// The grid for `state`: none (two slabs along a random axis per cut) below kGridFrom
  /// particles; else about N / kParticlesPerDomain domains, cutting
  /// first the axes along which the domains stay widest next to the particles' mean lab extent
  /// (never narrower than 3 extents), so that few particles straddle a cut. A nematic of rods
  /// along z is cut along x and y only.
  static std::optional<Layout> automatic_layout(const State& state);
  /// Fixes the layout: a grid, or none for two slabs along a random axis. Without a call, the
  /// first cycle takes automatic_layout of its state; the layout then stays for the run.
  void set_layout(const std::optional<Layout>& grid);
  /// The layout in force (set or chosen), if any has been.
  bool layout_chosen() const { return layout_chosen_; }
  const std::optional<Layout>& layout() const { return grid_; }

  /// One cycle on `state`: N trial moves, shared equally between the domains that have movable
  /// particles. Draws a new cut (when the last one has served its cycles) and the domain seeds
  /// from `rng`; adds to `counters`. `state` must not have changed since the last cycle unless
  /// invalidate() was called (a changed box is noticed anyway).
  void cycle(State& state, Rng& rng, const MoveSizes& moves, const OrientationalField& field, bool removing_overlaps,
             MoveCounters& counters);
  /// Up to `wanted` cycles at once, as many as remain in the cut in use (or in a new one): the
  /// same bits as that many calls of cycle(), with each domain's cycles run back to back, so that
  /// its copy is read from cache after the first. Nothing may change the state in between (no
  /// volume moves). Returns the number of cycles run (≥ 1).
  int cycles(State& state, Rng& rng, int wanted, const MoveSizes& moves, const OrientationalField& field, bool removing_overlaps,
             MoveCounters& counters);
  /// The configuration changed behind the domains' copies (a volume move): copy them again before
  /// the next cycle, under the same cut.
  void invalidate() { copies_valid_ = false; }

  /// The cut for a checkpoint (none before the first cycle and after a cut's last cycle) ...
  const std::optional<Cut>& cut() const { return cut_; }
  /// ... and back: the next cycles continue it, so a resumed run repeats the uninterrupted one.
  void restore_cut(const std::optional<Cut>& cut);

 private:
  /// A domain's own copy of the particles that reach into it.
  struct Part {
    Domain domain;  // the cut
    Domain inner;   // the cut less a margin far above round-off: where movable bodies stay
    Domain outer;   // the cut plus that margin: the bodies that reach into it are copied
    State sub;
    std::optional<HardOverlap> overlap;
    std::vector<std::int32_t> global;   // sub index → index in the full state
    std::vector<std::int32_t> movable;  // sub indices of the particles inside the domain
    MoveCounters counters;
  };
  Cut draw_cut(Rng& rng) const;
  /// Copies every domain of the current cut and builds its neighbour search.
  void copy_domains(const State& state);
  static void set_bounds(Part& part, const Vec3& L);
  /// Lists in each part's `global` the particles whose lab boxes reach into its domain.
  void bin_particles(const State& state);
  /// The indices of the domains along `axis` that the interval [c − h, c + h] reaches.
  void reached_along(int axis, double c, double h, double L, std::vector<int>& out) const;
  /// The part's copy of its listed particles, and which of them are movable.
  void copy_part(const State& state, Part& part) const;
  /// `trials` trial moves in the part's copy, from the stream seeded by `seed`.
  static void sweep(Part& part, std::uint64_t seed, std::int64_t trials, const MoveSizes& moves, const OrientationalField& field,
                    bool removing_overlaps);
  /// Copies the part's movable particles back into `state`.
  static void write_back(State& state, const Part& part);

  bool layout_chosen_ = false;
  std::optional<Layout> grid_;
  std::optional<Cut> cut_;
  bool copies_valid_ = false;
  Vec3 copied_edges_ = Vec3::Zero();  // the box the copies were made in
  std::vector<Part> parts_;
  std::vector<std::uint64_t> seeds_;
  std::vector<Vec3> half_extent_;  // per particle: lab half-extents
};

}  // namespace anisodyn

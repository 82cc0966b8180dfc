#pragma once
// Metropolis Monte Carlo for hard particles (spec 10 §3): single-particle trial moves — a
// body-frame translation or a body-frame rotation, chosen at random for anisotropic particles — and,
// at constant pressure, volume moves in ln V (isotropic or one box axis at a time). Move sizes may
// be tuned towards a target acceptance; that is for preparation runs only (never in DMC).
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "anisodyn/core/rng.hpp"
#include "anisodyn/interactions/hard_overlap.hpp"
#include "anisodyn/interactions/orientational_field.hpp"
#include "anisodyn/mc/domain_sweep.hpp"
#include "anisodyn/mc/trial_move.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn {

enum class BoxMoves { Isotropic, PerAxis };

class McEngine {
 public:
  /// The engine works on `state` in place. Throws InputError if the configuration overlaps.
  McEngine(State& state, const RngState& rng);

  void set_field(const OrientationalField& field) { field_ = field; }
  /// Constant-pressure moves with βP (in the study's length unit), or none for NVT.
  void set_pressure(std::optional<double> beta_pressure, BoxMoves moves = BoxMoves::Isotropic);

  /// One cycle: N particle trial moves, plus on average one volume move under NPT. With domain
  /// sweeps, the particle moves are one DomainSweep cycle (two slabs, or a grid of domains for
  /// large systems, on all threads); under NPT each such cycle owes one volume move, and the owed
  /// moves are made one after another when the cut ends (under the pressure in force then; none
  /// if it is a constant-volume phase by then), so that a cut's cycles run on the same copies, in
  /// one batch, as under NVT. The engine does not see changes made to the state behind its back.
  void cycle();
  /// Up to `wanted` cycles at once, with the bits of as many calls of cycle(): domain sweeps run
  /// each domain's cycles back to back, within one cut (DomainSweep::cycles); otherwise one
  /// cycle. Returns the number of cycles run (≥ 1).
  int cycles(int wanted);
  /// Volume moves owed by the domain cycles of the cut in use (NPT with domain sweeps), for a
  /// checkpoint; restore() takes them back.
  int volume_moves_owed() const { return volume_moves_owed_; }
  /// Domain sweeps on or off (off: the sequential random choice, the default). Preparation only:
  /// the trajectory differs from the sequential one, the distribution sampled does not.
  void set_domain_sweeps(bool on);
  /// Whether domain sweeps are on: then, and only then, cycles() runs more than one cycle at once.
  bool domain_sweeps() const { return domains_ != nullptr; }
  /// Scales every move size by acceptance/target (bounded by a factor 2 either way), using the
  /// acceptance counted in `window`.
  void tune(double target_acceptance, const MoveCounters& window);

  /// Affine isotropic rescaling of the box to `volume`, accepted only if it creates no overlap.
  bool try_rescale(double volume);

  /// Quick compression (preparation only, not an equilibrium sampler): rescales the box even if
  /// particles then overlap ...
  void rescale_allowing_overlaps(double volume);
  /// ... and, while on, lets a particle with overlaps move only if that lowers its number of
  /// overlaps (a clean particle only to a clean place), so sweeps remove the overlaps.
  void set_overlap_removal(bool on) { removing_overlaps_ = on; }

  MoveSizes& move_sizes() { return moves_; }
  const MoveSizes& move_sizes() const { return moves_; }
  /// Restores what a checkpoint saved, so the run continues bit-for-bit (domain sweeps restore
  /// their layout and cut through domain_sweep()).
  void restore(const RngState& rng, const MoveCounters& counters, const MoveSizes& moves, int volume_moves_owed = 0);
  /// The domain sweeps (null without), for their checkpoint and their layout.
  DomainSweep* domain_sweep() { return domains_.get(); }
  const DomainSweep* domain_sweep() const { return domains_.get(); }
  /// Cumulative counters since construction.
  const MoveCounters& counters() const { return counters_; }
  const RngState& rng_state() const { return rng_.state(); }
  const State& state() const { return state_; }
  /// Total field energy βU of the configuration.
  double field_energy() const;
  const HardOverlap& overlap() {
    refresh_overlap();
    return overlap_;
  }

 private:
  void particle_move();
  void volume_move();
  /// Brings the neighbour structures up to date after domain sweeps moved particles behind them.
  void refresh_overlap();
  /// Re-reads every position and orientation into the neighbour structures (refitted trees,
  /// HardOverlap::refresh), telling them of the moves the domain sweeps made.
  void update_overlap();
  /// Domain sweeps made these moves behind the neighbour structures.
  void note_unseen_moves(const MoveCounters& made);
  /// The domain sweeps' cycles, counting their moves as unseen; under NPT each owes a volume
  /// move, and the owed moves are made when the cut ends.
  int domain_cycles(int wanted);
  /// Makes the owed volume moves now.
  void settle_volume_moves();
  /// A rescaled box was kept: the domain sweeps' slab copies are out of date.
  void box_rescaled();
  /// After every position was rescaled (or restored): refreshes the overlap search now or marks it
  /// stale (domain sweeps).
  void positions_rescaled();
  /// Rescales the box and positions to `new_edges`; if that creates an overlap, restores the
  /// previous box and the saved positions bit for bit and returns true.
  bool any_overlap_after_rescale(const Vec3& new_edges);
  void rescale_positions(const Vec3& factor);
  /// Puts particle i first among the suspects the next compression check queries first.
  void suspect(std::int32_t i);
  /// Witnesses of recent failed compressions kept as suspects: a compression that fails usually
  /// fails on a pair already close to contact, which the next ones tend to meet again.
  static constexpr std::size_t kSuspects = 32;
  State& state_;
  Rng rng_;
  HardOverlap overlap_;
  OrientationalField field_;
  std::optional<double> beta_pressure_;
  bool removing_overlaps_ = false;
  BoxMoves box_moves_ = BoxMoves::Isotropic;
  MoveSizes moves_;
  MoveCounters counters_;
  std::unique_ptr<DomainSweep> domains_;
  bool overlap_stale_ = false;
  int volume_moves_owed_ = 0;
  std::vector<std::int64_t> unseen_moves_;  // per species: accepted moves overlap_ was not told of
  std::vector<double> saved_x_, saved_y_, saved_z_;  // positions before a trial rescaling
  std::vector<std::int32_t> suspects_;  // most recent first; which ones does not change the outcome
};

}  // namespace anisodyn

#pragma once
// The Groot–Warren DPD pair forces between liquid particles (spec 30 §2), as a force field an
// integrator calls (integrate/body_forces.hpp). For r = |r_i − r_j| < r_c, r̂ = (r_i − r_j)/r,
// v_ij = v_i − v_j and w = 1 − r/r_c, the force on i is the sum of three parts along r̂:
//
//   conservative  F^C = a w r̂                          (pair energy a r_c w²/2)
//   dissipative   F^D = −γ w² (r̂·v_ij) r̂
//   random        F^R = √(2 γ kT) w θ_ij Δt^{−1/2} r̂
//
// θ_ij is a unit normal from the pair noise (core/pair_noise.hpp), addressed by the noise
// step and the two particles' ids: the same for (i, j) and (j, i), whatever the thread count or the
// order of the pairs.
//
// Why a kernel of its own rather than a pair evaluator of interactions/pair_forces.hpp: the liquid
// is nearly all of a DPD run's work (spec 30's boxes hold 10²–10⁴ liquid particles per colloid),
// and the generic loop's per-pair records (three force vectors, torques, energy) and per-part
// virial tensors cost four times LAMMPS's whole step (docs/performance.md). Here the particles are
// taken in the cell order of the pair list (neighbors/cell_ordered_pairs.hpp), copied into arrays
// of that order each step, so that partners are near each other in memory. Every pair is
// evaluated once, from its lower position, and its force added to both positions at once. Each
// thread owns a contiguous block of positions; a pair that reaches into a later block is evaluated
// first, by the same code, into its slot (these pairs of all blocks shared out evenly between the
// threads), and the owner of its upper position takes it before its own pairs. So every position
// adds the opposites of its pairs from below (ascending), then its pairs above (ascending),
// whatever the number of threads, and both particles of a pair get
// exactly opposite forces: Newton's third law holds pair by pair. The virial (by part, its six
// independent elements: r_ij ⊗ F_ij is symmetric for central forces) and the energy are summed per
// group of kRowsPerGroup positions (blocks hold whole groups; each a sum over the group's pairs with
// eight partial sums in a fixed order, which vectorises) and reduced in group order. Only the
// liquid particles that set_liquid() names take part (all, by default). The order is a function of the
// positions at the list's last build, which a checkpoint keeps (list_positions), so a resumed run
// adds in the same order.
//
// The velocities are those in the state when the forces are evaluated: in velocity Verlet the
// half-step ones, which is LAMMPS's scheme and Groot–Warren's with λ = ½, or with another λ the
// predicted ones (integrate/rigid_body_nve.hpp, docs/dpd.md).
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "anisodyn/core/pair_noise.hpp"
#include "anisodyn/integrate/body_forces.hpp"
#include "anisodyn/neighbors/cell_ordered_pairs.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn {

/// The liquid's DPD parameters (spec 30 §2 in reduced units: r_c = m = kT = 1).
struct DpdParameters {
  double a = 25.0;      // conservative repulsion
  double gamma = 4.5;   // dissipative friction
  double kT = 1.0;
  double cutoff = 1.0;  // r_c
};

/// Purpose tag of the DPD pair noise in the keyed generator (other noises of a run take others).
inline constexpr std::uint64_t kDpdPairNoise = 0x44504450414952ULL;  // "DPDPAIR"

/// Energy and virial of one evaluation. virial[k] holds Σ_{i<j} r_ij ⊗ F_ij of part k
/// (conservative, dissipative, random), r_ij = r_i − r_j and F_ij the force on i.
struct DpdSums {
  double energy = 0.0;
  std::array<Mat3, 3> virial{Mat3::Zero(), Mat3::Zero(), Mat3::Zero()};
};

class DpdForceField {
 public:
  /// Every particle is liquid unless set_liquid() says which are; seed keys the pair noise.
  DpdForceField(DpdParameters params, double time_step, std::uint64_t seed, double skin);

  /// The liquid particles (indices into the state, ascending; none: colloids alone); the others
  /// (colloids) get no DPD force. Until it is called, every particle is liquid.
  void set_liquid(std::vector<std::int32_t> indices);

  /// Adds the DPD forces of state s into out (forces, energy, virial summed over the parts).
  void operator()(const State& s, BodyForces& out);

  /// The draws of the next evaluation are those of this step (the engine sets it before each).
  void set_noise_step(std::uint64_t step) { noise_step_ = step; }
  const DpdSums& last_sums() const { return sums_; }
  const CellOrderedPairs& list() const { return list_; }
  /// The positions of the list's last build (for a checkpoint), and the list rebuilt from them.
  std::vector<double> list_positions() const { return list_.built_positions(); }
  void restore_list(const Box& box, const std::vector<double>& positions) { list_.rebuild_at(box, positions); }
  const DpdParameters& parameters() const { return p_; }

 private:
  /// The state index of liquid particle u.
  std::size_t particle(std::size_t u) const { return subset_ ? static_cast<std::size_t>(liquid_[u]) : u; }
  /// The pair list of the n liquid particles' positions, rebuilt when stale.
  void update_list(const State& s, std::size_t n);
  /// Copies the n liquid particles into the arrays of the list's order.
  void gather(const Particles& p, std::size_t n);
  /// All the pairs of the block of rows [begin, end), into force_ (both positions when both are
  /// below end) and the rows' sums.
  void rows(std::size_t begin, std::size_t end, const Box& box);
  /// Pairs m_begin … m_end − 1 of row k; first_candidate: their place among the group's pairs.
  struct RowTask {
    std::size_t k, m_begin, m_end, first_candidate;
  };
  /// The pairs of rows [begin, end) that reach past end, one task per row, numbered in order.
  void find_cross_tasks(std::size_t begin, std::size_t end, std::vector<RowTask>& cross) const;
  /// Part `share` of `shares` (equal in candidates) of all the blocks' cross tasks, into their slots.
  void cross_share(int share, int shares, const Box& box);
  /// Evaluates a group of row tasks, the noise of all their pairs in one batch: with cross_only
  /// into their slots, otherwise into force_ (both positions when both are below block_end) and
  /// the rows' sums. One compiled body for both, so that a pair's force has the same bits either way.
  [[gnu::noinline]] void row_forces(const RowTask* tasks, std::size_t count, std::size_t block_end, bool cross_only, const Box& box);

  /// Rows evaluated together (one batch of noise) and summed together.
  static constexpr std::size_t kRowsPerGroup = 32;
  /// Per-group sums over the group's pairs: energy, then 3 parts × 6 virial elements.
  static constexpr int kSums = 19;

  DpdParameters p_;
  double noise_amplitude_;  // √(2γkT/Δt)
  PairNoise noise_;
  CellOrderedPairs list_;
  std::vector<std::int32_t> liquid_;        // when subset_: the liquid particles
  bool subset_ = false;
  std::vector<double> lx_, ly_, lz_;        // the liquid's positions, for the list (when a subset)
  std::uint64_t noise_step_ = 0;
  // Per position of the list's order: positions, velocities, ids.
  std::vector<double> x_, y_, z_, vx_, vy_, vz_;
  std::vector<std::uint32_t> id_;
  std::unique_ptr<double[]> slot_force_;  // 3 per listed pair: the force on the lower position (pairs across blocks only)
  std::size_t slot_capacity_ = 0;
  std::vector<std::vector<RowTask>> cross_tasks_;  // per block: its pairs across blocks
  std::int64_t cross_builds_ = -1;                 // the list build and block count they are of
  int cross_blocks_ = 0;
  std::vector<double> force_;       // 3 per position
  std::vector<double> partial_;     // kSums per group of kRowsPerGroup positions
  DpdSums sums_;
};

}  // namespace anisodyn

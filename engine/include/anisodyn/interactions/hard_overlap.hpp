#pragma once
// Hard-core exclusion for a whole configuration: the cell list, cached rotation matrices, the
// per-species-pair cut-offs (sum of circumradii) and, for engines with small moves, skin lists
// (neighbors/skin_list.hpp). Contact counts as overlap (spec 10 §1.4).
//
// Candidates of species b come from b's cell grid unless a query of some species a would make
// that grid visit every cell (long particles in a box a few cut-offs wide) or search a volume
// much larger than the lab boxes of a and b (long particles, aligned or not, in any box); then from
// an AABB tree over b's lab boxes (neighbors/aabb_tree.hpp), chosen per pair (a, b) at every
// rebuild and rebuilt after as many accepted moves as b has particles. Both hand the overlap kernels the separations the
// grid's all-cells scan formed, so the outcomes are the same bits either way.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "anisodyn/core/types.hpp"
#include "anisodyn/neighbors/aabb_tree.hpp"
#include "anisodyn/neighbors/cell_list.hpp"
#include "anisodyn/neighbors/skin_list.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn {

/// Largest centre distance at which any two particles of these species can touch.
double largest_pair_cutoff(const SpeciesTable& species);

/// InputError(file, "/particles/all/box", …) unless every box edge is at least twice the largest
/// pair cut-off, which the minimum-image convention needs.
void require_minimum_image(const State& state, const std::string& file);

class HardOverlap {
 public:
  /// Throws InputError if some species pair has no overlap test.
  /// expected_counts (per species) sizes the cell grids for particles still to be inserted.
  explicit HardOverlap(const State& state, const std::vector<std::size_t>& expected_counts = {});

  /// Lists the partners of species s within skin half-width half_skin[s] (0: search the cell
  /// grid at every query, the default). A pair of species is listed when both have a skin,
  /// except sphere–sphere pairs. Pays when moves are small next to the skin; outcomes are the
  /// same either way.
  void use_skin_lists(std::vector<double> half_skin);
  const SkinList& skin_lists() const { return skin_; }

  /// Re-reads every position and orientation (after a box change or a bulk edit).
  void rebuild(const State& state);
  /// rebuild() for particles that have all moved a little (MC moves made elsewhere, a rescaled
  /// box): the trees are refitted, not rebuilt, and the searches chosen at the last rebuild are
  /// kept, until a tree has seen as many moves as it holds particles (unseen_moves per species:
  /// accepted moves this object was not told of) or a box edge has changed by more than 2%;
  /// then it rebuilds. The outcomes are the same bits either way.
  void refresh(const State& state, const std::vector<std::int64_t>& unseen_moves);
  /// Registers particle i, just appended to the state (insertion during configuration building).
  void inserted(std::int32_t i);
  /// Whether particle i placed at r (wrapped) with rotation matrix rot overlaps any other particle.
  bool overlaps(std::int32_t i, const Vec3& r, const Mat3& rot) const;
  /// Number of particles that particle i, placed at r with rotation rot, overlaps (full scan).
  int count_overlaps(std::int32_t i, const Vec3& r, const Mat3& rot) const;
  /// Records an accepted move of particle i.
  void moved(std::int32_t i, const Vec3& r, const Mat3& rot);
  /// First overlapping pair (i < j) of the configuration, if any.
  std::optional<std::pair<std::int32_t, std::int32_t>> first_overlap() const;
  /// Whether any two particles overlap: first_overlap() as a yes or no, checked on all OpenMP
  /// threads (the answer does not depend on their number). For the checks after a volume move.
  bool any_overlap() const;
  /// A particle i whose query finds an overlap with some j > i, or none: any_overlap() with a
  /// witness. The particles in `suspects` are queried first, one after the other, the rest on all
  /// OpenMP threads; which witness comes back may depend on the threads, whether one does not.
  /// After a rejected volume move, the next compression tends to fail on the same pairs.
  std::optional<std::int32_t> overlapping_particle(const std::vector<std::int32_t>& suspects = {}) const;

  const Mat3& rotation(std::int32_t i) const { return rot_[static_cast<std::size_t>(i)]; }
  double cutoff(int a, int b) const { return cutoff_[static_cast<std::size_t>(a * nspecies_ + b)]; }
  /// Largest pair cut-off: minimum image needs every box edge ≥ twice this.
  double max_cutoff() const { return largest_cutoff_; }
  /// Whether queries of species a search species b through its AABB tree (else its cell grid).
  bool uses_tree(int a, int b) const { return tree_pair_[static_cast<std::size_t>(a * nspecies_ + b)] != 0; }

 private:
  /// Whether particle i's query (partners j > i, at its current placement) finds an overlap.
  bool overlaps_later(std::int32_t i) const;
  /// Calls on_overlap(j) for each particle j ≠ i, j ≥ first_j, that particle i placed at (r, rot)
  /// overlaps, until on_overlap returns true; returns whether it stopped early.
  template <class F>
  bool for_each_overlap(std::int32_t i, const Vec3& r, const Mat3& rot, std::int32_t first_j, F&& on_overlap) const;

  /// Calls f(j, d, r2) for the partners of species b on i's skin list with r2 ≤ rc², d formed as
  /// the cell list forms it; stops when f returns true.
  /// Calls f(j, d, r2) for the particles of species b whose lab boxes meet that of a body of
  /// species a at (r, rot) and whose centres lie within rc, from b's AABB tree.
  template <class F>
  bool visit_tree(int a, int b, const Vec3& r, const Mat3& rot, double rc, F&& f) const;
  template <class F>
  bool visit_listed(std::int32_t i, int b, const Vec3& r, double rc, F&& f) const;
  void rebuild_skin_lists();
  /// Makes i's current placement its reference and finds its listed partners.
  void rereference(std::int32_t i);
  /// Links i (whose reference is set) with every referenced j ≥ first_j whose grown reference
  /// body overlaps i's.
  void link_partners(std::int32_t i, std::int32_t first_j);
  /// Chooses grid or tree per species pair and builds the trees needed: the tree where the grid
  /// would visit every cell, or a volume kTreeAdvantage times what the tree's box test keeps.
  void choose_searches();
  /// A tree candidate costs more than a grid candidate (a node walk against a vectorised
  /// distance pass): the grid keeps pairs whose searched volume is within this factor of the
  /// tree's. Measured (bench/mc_throughput.cpp, docs/performance.md): at a volume ratio of 3.6
  /// (spheres, η = 0.40) the grid is 3.3× faster, at 20 (boards 12×3.46×1, η = 0.20) 1.2×, at 19.5
  /// (boards 12×8×1, η = 0.34) as fast; at 115 (8000 rods 12×1×1, η = 0.34) the tree is 2.7×
  /// faster, at 364 (those rods' queries of 200 small spheres) 1.15×.
  static constexpr double kTreeAdvantage = 50.0;
  void build_trees();
  void rebuild_tree(int b);
  /// The centres and padded lab half-extents of species b, into the trees' scratch.
  void gather_tree_entries(int b);
  void configure_grids(const State& state);
  void compute_rotations(const Particles& p);
  /// Whether refresh() must rebuild: a tree due, a box changed by more than 2% since the searches
  /// were chosen, or nothing but grids (whose rebuild is a refill).
  bool refresh_needs_rebuild(const State& state, const std::vector<std::int64_t>& unseen_moves) const;
  /// Per species: whether some search reads its cell grid (after choose_searches).
  std::vector<char> grids_read() const;
  bool tree_needed(int b) const { return tree_needed_[static_cast<std::size_t>(b)] != 0; }
  /// Lab box half-widths of a body of species a with rotation rot, padded so that round-off can
  /// only add candidates.
  Vec3 bounding_half_extents(int a, const Mat3& rot) const;

  const State* state_;
  double largest_cutoff_ = 0.0;
  int nspecies_ = 0;
  std::vector<double> cutoff_;
  std::vector<Mat3> rot_;
  std::vector<std::size_t> expected_counts_;
  CellList cells_;
  SkinList skin_;
  std::vector<char> tree_pair_;              // per (a, b): a's queries search b's tree
  std::vector<char> tree_needed_;            // per species: some pair searches its tree
  std::vector<AabbTree> trees_;              // per species (empty unless needed)
  std::vector<std::size_t> moves_since_build_;  // per species with a tree
  Vec3 edges_at_choice_ = Vec3::Zero();         // the box when the searches were chosen
  std::vector<std::int32_t> tree_members_;      // rebuild_tree's scratch
  std::vector<Vec3> tree_centres_, tree_halves_;
};

}  // namespace anisodyn

#pragma once
// A Verlet list of point particles with one cut-off, over the particles renumbered cell by cell:
// the list for liquids (DPD), where nearly all the work is pairs of points.
//
// Why a list of its own rather than VerletList (verlet_list.hpp): a liquid's particles diffuse, so
// their index order is soon random in space; VerletList keeps that order, and every pair then
// reads memory far from its partner's, and its search visits all 27 cells to keep the pairs whose
// index is higher. Here, at each build, the particles are sorted by cell (counting sort, cells in
// x-fastest order): neighbours sit close in memory, and since a cell's particles are contiguous,
// "j above k" is "j in a cell of higher number, or later in the same cell", so the search visits
// the half of the neighbour cells with higher numbers (and the cell itself) only.
//
// Positions k = 0 … n − 1 are the sorted order; order()[k] is the particle at position k. Row k
// lists its partners above k (ascending) as pairs numbered consecutively from first_pair(k); the
// pairs where k is the upper partner are listed by number in lower_pairs(k) (ascending), so that a
// force loop can evaluate each pair once, from its lower position, and let the upper one gather it,
// in a fixed order for any thread count.
//
// Staleness: the list is rebuilt when some particle has moved more than skin/2 since the build (or
// the box or the count changed). The list is a function of the positions at the build alone, so a
// checkpoint that keeps them (built_positions) restores the same list, order and sums (rebuild_at).
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "anisodyn/core/box.hpp"
#include "anisodyn/core/types.hpp"

namespace anisodyn {

class CellOrderedPairs {
 public:
  /// Pairs closer than cutoff + skin at the build; skin > 0.
  CellOrderedPairs(double cutoff, double skin);

  /// Rebuilds when stale (see above) from the positions (x, y, z of n particles). Returns whether it
  /// rebuilt. The box must be at least 2 (cutoff + skin) along every edge (minimum image).
  bool update(const Box& box, const double* x, const double* y, const double* z, std::size_t n);
  /// The next update() rebuilds (the particles it lists changed).
  void invalidate() { built_x_.clear(); }
  /// Builds from positions given as x0, y0, z0, x1, … (a checkpoint's built_positions()).
  void rebuild_at(const Box& box, const std::vector<double>& positions);
  /// The positions of the last build, x0, y0, z0, x1, … (in particle order).
  std::vector<double> built_positions() const;

  std::size_t size() const { return order_.size(); }
  /// order()[k]: the particle at sorted position k.
  std::span<const std::int32_t> order() const { return order_; }
  /// position_of()[i]: the sorted position of particle i (the inverse of order()).
  std::span<const std::int32_t> position_of() const { return position_of_; }
  /// Partners of position k above k, ascending.
  std::span<const std::int32_t> partners_above(std::size_t k) const {
    return {partners_.data() + first_pair_[k], partners_.data() + first_pair_[k + 1]};
  }
  /// Number of the pair (k, partners_above(k)[0]); the others follow it.
  std::size_t first_pair(std::size_t k) const { return first_pair_[k]; }
  /// Numbers of the pairs (j, k) with j < k, ascending (that is, by ascending j).
  std::span<const std::int32_t> lower_pairs(std::size_t k) const {
    return {lower_.data() + lower_start_[k], lower_.data() + lower_start_[k + 1]};
  }
  std::size_t pairs() const { return partners_.size(); }
  std::int64_t builds() const { return builds_; }
  double cutoff() const { return cutoff_; }
  double skin() const { return skin_; }

 private:
  void build(const Box& box, const double* x, const double* y, const double* z, std::size_t n);
  void sort_into_cells(const Box& box, const double* x, const double* y, const double* z, std::size_t n);
  void find_pairs(const Box& box);
  void list_lower_pairs();
  /// Boundaries of `blocks` blocks of whole cells' rows with about the same search work each.
  std::vector<std::size_t> scan_blocks(int blocks) const;

  double cutoff_, skin_;
  Box box_;
  Int3 cells_ = Int3(0, 0, 0);
  std::vector<double> built_x_, built_y_, built_z_;   // particle order, as given (unwrapped)
  std::vector<double> sx_, sy_, sz_;                  // sorted order, wrapped into the box
  std::vector<std::int32_t> order_, position_of_, cell_of_;  // cell_of_[k]: cell of position k
  std::vector<std::int32_t> cell_start_;              // [cells + 1]
  // Per cell c: the cells a search from c visits, c itself and its distinct neighbours numbered
  // above it, as runs of consecutive cells [first, last] (ascending). Consecutive cells are
  // consecutive in the position order, so each run is one contiguous scan, and the partners come
  // out in the same ascending order as cell by cell (x neighbours merge: 14 cells make about 5 runs).
  std::vector<std::vector<std::pair<std::int32_t, std::int32_t>>> search_runs_;
  std::vector<std::size_t> first_pair_;               // [n + 1]
  std::vector<std::int32_t> partners_;
  std::vector<std::size_t> lower_start_;              // [n + 1]
  std::vector<std::int32_t> lower_;
  std::vector<std::size_t> lower_place_;             // per thread and position: the count, then the next place
  std::vector<std::vector<std::int32_t>> found_;      // per thread block: the pairs it found (a buffer that only grows)
  std::int64_t builds_ = 0;
};

}  // namespace anisodyn

#pragma once
// Cell lists for hard-particle MC, one grid per species.
//
// Why one grid per species: in a mixture of very different sizes (spheres of diameter 0.1 among
// 12×8×1 boards) a single grid sized by the largest cut-off puts thousands of small particles in
// each cell, and one sized by the smallest makes every large-particle query visit millions of
// cells. Here species b gets cells no smaller than its own self cut-off (and no more cells than a
// small multiple of its particle count); a query with any cut-off visits however many cells of
// that grid it needs. Every box edge may have its own cell count, so elongated boxes are fine.
//
// Each cell keeps copies of its particles' positions in fixed-capacity slots, so the candidate
// loop reads contiguous memory and vectorises. Positions are wrapped into [0, L). A query may bring
// a shape-specific filter on the separation (HardOverlap's cuboid reach test), which that loop
// evaluates too, and whose lab extent prunes the cells visited.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#if defined(__AVX__)
#include <immintrin.h>
#endif
#include <vector>

#include "anisodyn/core/box.hpp"
#include "anisodyn/core/types.hpp"

namespace anisodyn {

/// A candidate filter for SpeciesGrid::visit: keeps every particle within the cut-off.
/// A filter is keep(dx, dy, dz) → whether to hand the separation d on, plus extent(rc): per axis,
/// a bound on |d_k| of every kept d, at most rc.
struct KeepAll {
  bool operator()(double, double, double) const { return true; }
  Vec3 extent(double rc) const { return Vec3::Constant(rc); }
};

/// Cells of an (sx × sy × sz) stencil as index triples, ordered by distance from its centre.
/// The reference is into a per-thread cache that only grows, so it stays valid.
struct StencilCell {
  std::int8_t a, b, c;
};
const std::vector<StencilCell>& stencil_order(int sx, int sy, int sz);

class SpeciesGrid {
 public:
  /// Chooses the grid for `count` particles whose largest mutual cut-off is `self_cutoff`
  /// (geometry only: clear() makes it ready for insertions).
  void configure(const Box& box, double self_cutoff, std::size_t count);
  void clear();
  /// Frees nothing but holds no cells: the grid must not be visited, inserted into or moved in
  /// until clear(). For a species whose partners come from another search.
  void leave_empty();
  void insert(std::int32_t particle, const Vec3& r);
  void remove(std::int32_t particle);
  /// Moves a particle already in the grid (call after an accepted move).
  void move(std::int32_t particle, const Vec3& r);

  /// Calls f(j, d, r2) for every particle j of this grid with |d|² ≤ rc², where d = r_j − r is the
  /// minimum-image separation. Stops early and returns true as soon as f returns true.
  /// r must be wrapped into the box. `keep(dx, dy, dz)`, evaluated in the vectorised distance
  /// pass, drops further candidates before f sees them (a shape-specific reach test); it must be
  /// branch-free and inlinable.
  template <class F, class Keep = KeepAll>
  bool visit(const Box& box, const Vec3& r, double rc, F&& f, const Keep& keep = {}) const;

  const Int3& cells_per_axis() const { return n_; }
  /// Whether a query with cut-off rc visits every cell (its reach wraps an axis whole): the grid
  /// then scans every particle, and a search that does not (neighbors/aabb_tree.hpp) is better.
  bool scans_all_cells(double rc) const {
    for (int k = 0; k < 3; ++k)
      if (span(rc, k) >= n_[k] || span(rc, k) > kMaxSpan) return true;
    return false;
  }
  /// Volume of the cells a query with cut-off rc visits (the whole box when it scans all cells).
  double query_volume(double rc) const {
    double v = 1.0;
    for (int k = 0; k < 3; ++k) v *= std::min(span(rc, k), n_[k]) * h_[k];
    return v;
  }

 private:
  static constexpr int kMaxSpan = 16;
  /// Cells an extent e leaves unvisited at each end of an axis make, on average, reach − e/h of a
  /// cell: below this fraction (hard spheres: 0.02) pruning costs more than it saves.
  static constexpr double kWorthPruning = 0.1;
  static constexpr int kDirectScan = 4;  // cells with at most this many particles take the short pass (≤ capacity)
  /// Cells along axis k within reach of a query with cut-off rc, its own included.
  int span(double rc, int k) const { return 2 * static_cast<int>(std::ceil(rc * inv_h_[k])) + 1; }
  /// Fallback of visit() when the reach wraps a whole axis (small boxes): every cell, minimum image.
  template <class F, class Keep>
  bool visit_all_cells(const Box& box, const Vec3& r, double rc, F&& f, const Keep& keep) const;
  /// r2[s] = |p_s − q|² for the n slots at (px, py, pz), or kDropped where keep rejects p_s − q.
  template <class Keep>
  [[gnu::always_inline]] static void distance_pass(const double* px, const double* py, const double* pz, int n, const Vec3& q,
                                                   const Keep& keep, double* r2);
  /// Calls f(ids[s], p_s − q, r2[s]) for the slots s set in hits, in slot order, the separation
  /// minimum-imaged in min_image_box when it is given; stops when f returns true.
  template <class F>
  [[gnu::always_inline]] static bool visit_hits(std::uint32_t hits, const double* px, const double* py, const double* pz,
                                                const std::int32_t* ids, const Vec3& q, const double* r2,
                                                const Box* min_image_box, F& f);
  /// r² of a slot the candidate filter drops: fails every cut-off test.
  static constexpr double kDropped = std::numeric_limits<double>::infinity();
  /// Calls f for the particles of one cell within √rc2 of q that keep passes: separations p − q
  /// as they stand, or minimum-imaged in min_image_box when it is given.
  template <class F, class Keep>
  [[gnu::always_inline]] bool scan_cell(int cell, const Vec3& q, double rc2, const Box* min_image_box, F& f, const Keep& keep) const;

 public:
  std::size_t capacity() const { return capacity_; }

 private:
  int cell_of(const Vec3& r) const;
  /// Index in pos_ of the x value of a cell's slot (y: + capacity_, z: + 2 capacity_).
  std::size_t x_index(int cell, std::size_t slot) const { return 3 * static_cast<std::size_t>(cell) * capacity_ + slot; }
  Vec3 stored(std::size_t x) const { return Vec3(pos_[x], pos_[x + capacity_], pos_[x + 2 * capacity_]); }
  void store(std::size_t x, const Vec3& r) {
    pos_[x] = r.x();
    pos_[x + capacity_] = r.y();
    pos_[x + 2 * capacity_] = r.z();
  }
  void grow_capacity();
  void place(std::int32_t particle, int cell, const Vec3& r);

  Int3 n_ = Int3(1, 1, 1);
  Vec3 inv_h_ = Vec3::Ones();
  Vec3 h_ = Vec3::Ones();
  std::size_t capacity_ = 8;
  std::vector<std::int32_t> count_;              // particles per cell
  // Slot positions, one block per cell: its capacity_ x values, then the y values, then the z
  // values, so that a query's few cache lines per cell are adjacent (dense spheres hold about one
  // particle per cell, and separate x, y and z arrays cost three distant lines per cell).
  std::vector<double> pos_;
  std::vector<std::int32_t> sid_;                // slot particle index
  std::vector<std::int32_t> cell_, slot_;        // per particle (indexed by particle index)
};

/// All species' grids plus the particle → species map.
class CellList {
 public:
  /// self_cutoffs[s] is the largest centre distance at which two particles of species s can
  /// interact (e.g. twice the circumradius).
  void build(const Box& box, const std::vector<double>& x, const std::vector<double>& y,
             const std::vector<double>& z, const std::vector<std::int32_t>& species,
             const std::vector<double>& self_cutoffs, const std::vector<std::size_t>& expected_counts = {});
  /// build() in two steps: the grids' geometry (grid(s) answers scans_all_cells and
  /// query_volume) ...
  void configure(const Box& box, const std::vector<std::int32_t>& species, const std::vector<double>& self_cutoffs,
                 const std::vector<std::size_t>& expected_counts = {});
  /// ... then the particles of the species with filled[s] placed; the other grids stay empty (see
  /// SpeciesGrid::leave_empty) and filled(s) says so.
  void fill(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& z,
            const std::vector<char>& filled);
  bool filled(int species) const { return filled_[static_cast<std::size_t>(species)] != 0; }
  /// Adds particle `particle` of `species` (its index must be the next unused one).
  void insert(std::int32_t particle, int species, const Vec3& r);
  void move(std::int32_t particle, const Vec3& r) { grids_[species_[particle]].move(particle, r); }

  template <class F, class Keep = KeepAll>
  bool visit(int species, const Vec3& r, double rc, F&& f, const Keep& keep = {}) const {
    return grids_[species].visit(box_, r, rc, std::forward<F>(f), keep);
  }
  const SpeciesGrid& grid(int species) const { return grids_[species]; }
  const Box& box() const { return box_; }

 private:
  Box box_;
  std::vector<SpeciesGrid> grids_;
  std::vector<std::int32_t> species_;
  std::vector<char> filled_;
};

// ---- inline implementation of the hot loop ----------------------------------------------------

/// Bit s set where v[s] ≤ limit (s < n ≤ 32); false for NaN. Compilers turn the scalar form into
/// one comparison and extraction per element, so groups of four use one vector comparison.
[[gnu::always_inline]] inline std::uint32_t at_most_mask(const double* v, int n, double limit) {
  std::uint32_t mask = 0;
  int s = 0;
#if defined(__AVX__)
  const __m256d l = _mm256_set1_pd(limit);
  for (; s + 4 <= n; s += 4)
    mask |= static_cast<std::uint32_t>(_mm256_movemask_pd(_mm256_cmp_pd(_mm256_loadu_pd(v + s), l, _CMP_LE_OQ))) << s;
#endif
  for (; s < n; ++s) mask |= static_cast<std::uint32_t>(v[s] <= limit) << s;
  return mask;
}

template <class F, class Keep>
bool SpeciesGrid::visit(const Box& box, const Vec3& r, double rc, F&& f, const Keep& keep) const {
  // Per axis, the cells within the cut-off's reach, of which only those that meet [r − e, r + e]
  // are visited, e being keep's extent (at most rc) grown by a margin far above round-off, so that
  // no cell holding a kept candidate is missed. When no axis is wrapped whole (the usual case)
  // each visited cell has one periodic image next to r, so the separation is p + shift − r with
  // no rounding; otherwise every cell is visited once and the minimum image is taken per candidate.
  int cells[3][kMaxSpan];
  double shift[3][kMaxSpan];
  std::uint32_t meets[3];  // bit a: cell a of the axis meets [r − e, r + e]
  int spans[3];
  const Vec3& L = box.edges();
  const Vec3 e = keep.extent(rc) * (1.0 + 1e-9) + Vec3::Constant(1e-9 * rc);
  for (int k = 0; k < 3; ++k) {
    const int reach = static_cast<int>(std::ceil(rc * inv_h_[k]));
    spans[k] = 2 * reach + 1;
    if (spans[k] >= n_[k] || spans[k] > kMaxSpan) return visit_all_cells(box, r, rc, std::forward<F>(f), keep);
    const int c = std::min(static_cast<int>(r[k] * inv_h_[k]), n_[k] - 1);
    if (e[k] * inv_h_[k] > reach - kWorthPruning) {
      meets[k] = ~0u;
    } else {
      const int lo = std::max(0, static_cast<int>(std::floor((r[k] - e[k]) * inv_h_[k])) - c + reach);
      const int hi = std::min(spans[k] - 1, static_cast<int>(std::floor((r[k] + e[k]) * inv_h_[k])) - c + reach);
      meets[k] = ((2u << hi) - 1u) & ~((1u << lo) - 1u);
    }
    for (int a = 0; a < spans[k]; ++a) {
      const int cc = c - reach + a;
      cells[k][a] = cc < 0 ? cc + n_[k] : (cc >= n_[k] ? cc - n_[k] : cc);
      shift[k][a] = cc < 0 ? -L[k] : (cc >= n_[k] ? L[k] : 0.0);
    }
  }
  // Nearest cells first: most trial moves are rejected, and a rejection ends at the first overlap,
  // which is usually in the query's own cell or a face neighbour.
  for (const auto& [a, b, c] : stencil_order(spans[0], spans[1], spans[2])) {
    if (((meets[0] >> a) & (meets[1] >> b) & (meets[2] >> c) & 1u) == 0) continue;
    const int cell = (cells[0][a] * n_[1] + cells[1][b]) * n_[2] + cells[2][c];
    const Vec3 q(r.x() - shift[0][a], r.y() - shift[1][b], r.z() - shift[2][c]);
    if (scan_cell(cell, q, rc * rc, nullptr, f, keep)) return true;
  }
  return false;
}

template <class F, class Keep>
bool SpeciesGrid::visit_all_cells(const Box& box, const Vec3& r, double rc, F&& f, const Keep& keep) const {
  const int cells = n_.prod();
  for (int cell = 0; cell < cells; ++cell)
    if (scan_cell(cell, r, rc * rc, &box, f, keep)) return true;
  return false;
}

template <class Keep>
[[gnu::always_inline]] inline void SpeciesGrid::distance_pass(const double* px, const double* py, const double* pz, int n, const Vec3& q,
                                                              const Keep& keep, double* r2) {
  // Without branches so it vectorises; hits are handled afterwards.
#pragma omp simd
  for (int s = 0; s < n; ++s) {
    const double dx = px[s] - q.x(), dy = py[s] - q.y(), dz = pz[s] - q.z();
    const double d2 = dx * dx + dy * dy + dz * dz;
    r2[s] = keep(dx, dy, dz) ? d2 : kDropped;
  }
}

template <class F>
[[gnu::always_inline]] inline bool SpeciesGrid::visit_hits(std::uint32_t hits, const double* px, const double* py, const double* pz,
                                                           const std::int32_t* ids, const Vec3& q, const double* r2,
                                                           const Box* min_image_box, F& f) {
  while (hits != 0) {
    const int s = __builtin_ctz(hits);
    hits &= hits - 1;
    Vec3 d(px[s] - q.x(), py[s] - q.y(), pz[s] - q.z());
    if (min_image_box != nullptr) d = min_image_box->min_image(d);
    if (f(ids[s], d, r2[s])) return true;
  }
  return false;
}

template <class F, class Keep>
[[gnu::always_inline]] inline bool SpeciesGrid::scan_cell(int cell, const Vec3& q, double rc2, const Box* min_image_box, F& f,
                                                          const Keep& keep) const {
  const int m = count_[cell];
  const std::size_t base = static_cast<std::size_t>(cell) * capacity_;
  const double* xs = pos_.data() + x_index(cell, 0);
  const double* ys = xs + capacity_;
  const double* zs = ys + capacity_;
  const std::int32_t* ids = sid_.data() + base;
  if (m <= kDirectScan && min_image_box == nullptr) {
    // Few slots (dense spheres hold about one per cell): all kDirectScan slots in one short
    // vector pass, with no branch on the count, which half-empty cells would mispredict. Empty
    // slots hold NaN and fail the cut-off test.
    double r2[kDirectScan];
    distance_pass(xs, ys, zs, kDirectScan, q, keep, r2);
    return visit_hits(at_most_mask(r2, kDirectScan, rc2), xs, ys, zs, ids, q, r2, nullptr, f);
  }
  // The distances of a chunk of slots go to a buffer on the stack, so that visits from several
  // threads (a Verlet list built in parallel) share nothing.
  constexpr int kChunk = 32;
  double r2[kChunk];
  for (int s0 = 0; s0 < m; s0 += kChunk) {
    const int mm = std::min(kChunk, m - s0);
    if (min_image_box == nullptr) {
      distance_pass(xs + s0, ys + s0, zs + s0, mm, q, keep, r2);
    } else {
      const double *px = xs + s0, *py = ys + s0, *pz = zs + s0;
      const Vec3& L = min_image_box->edges();
      const Vec3& invL = min_image_box->inverse_edges();
#pragma omp simd
      for (int s = 0; s < mm; ++s) {
        double dx = px[s] - q.x(), dy = py[s] - q.y(), dz = pz[s] - q.z();
        dx -= L.x() * std::nearbyint(dx * invL.x());
        dy -= L.y() * std::nearbyint(dy * invL.y());
        dz -= L.z() * std::nearbyint(dz * invL.z());
        const double d2 = dx * dx + dy * dy + dz * dz;
        r2[s] = keep(dx, dy, dz) ? d2 : kDropped;
      }
    }
    // Hits as a bit mask, then visited in slot order: no branch per slot to mispredict (about one
    // slot in ten is a hit for boards, whose cells are sized by their length).
    if (visit_hits(at_most_mask(r2, mm, rc2), xs + s0, ys + s0, zs + s0, ids + s0, q, r2, min_image_box, f)) return true;
  }
  return false;
}

}  // namespace anisodyn

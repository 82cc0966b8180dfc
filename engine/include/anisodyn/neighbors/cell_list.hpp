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
// loop reads contiguous memory and vectorises. Positions are wrapped into [0, L).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "anisodyn/core/box.hpp"
#include "anisodyn/core/types.hpp"

namespace anisodyn {

/// Cells of an (sx × sy × sz) stencil as index triples, ordered by distance from its centre.
/// The reference is into a per-thread cache that only grows, so it stays valid.
struct StencilCell {
  std::int8_t a, b, c;
};
const std::vector<StencilCell>& stencil_order(int sx, int sy, int sz);

class SpeciesGrid {
 public:
  /// Chooses the grid for `count` particles whose largest mutual cut-off is `self_cutoff`.
  void configure(const Box& box, double self_cutoff, std::size_t count);
  void clear();
  void insert(std::int32_t particle, const Vec3& r);
  void remove(std::int32_t particle);
  /// Moves a particle already in the grid (call after an accepted move).
  void move(std::int32_t particle, const Vec3& r);

  /// Calls f(j, d, r2) for every particle j of this grid with |d|² ≤ rc², where d = r_j − r is the
  /// minimum-image separation. Stops early and returns true as soon as f returns true.
  /// r must be wrapped into the box. Not thread-safe (uses a scratch buffer): one grid per thread.
  template <class F>
  bool visit(const Box& box, const Vec3& r, double rc, F&& f) const;

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
  static constexpr int kDirectScan = 4;  // cells with at most this many particles skip the vector pass
  /// Cells along axis k within reach of a query with cut-off rc, its own included.
  int span(double rc, int k) const { return 2 * static_cast<int>(std::ceil(rc * inv_h_[k])) + 1; }
  /// Fallback of visit() when the reach wraps a whole axis (small boxes): every cell, minimum image.
  template <class F>
  bool visit_all_cells(const Box& box, const Vec3& r, double rc, F&& f) const;
  /// Calls f for the particles of one cell within √rc2 of q: separations p − q as they stand, or
  /// minimum-imaged in min_image_box when it is given.
  template <class F>
  [[gnu::always_inline]] bool scan_cell(int cell, const Vec3& q, double rc2, const Box* min_image_box, F& f) const;

 public:
  std::size_t capacity() const { return capacity_; }

 private:
  int cell_of(const Vec3& r) const;
  void grow_capacity();
  void place(std::int32_t particle, int cell, const Vec3& r);

  Int3 n_ = Int3(1, 1, 1);
  Vec3 inv_h_ = Vec3::Ones();
  Vec3 h_ = Vec3::Ones();
  std::size_t capacity_ = 8;
  std::vector<std::int32_t> count_;              // particles per cell
  std::vector<double> sx_, sy_, sz_;             // slot positions, cell-major
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
  /// Adds particle `particle` of `species` (its index must be the next unused one).
  void insert(std::int32_t particle, int species, const Vec3& r);
  void move(std::int32_t particle, const Vec3& r) { grids_[species_[particle]].move(particle, r); }

  template <class F>
  bool visit(int species, const Vec3& r, double rc, F&& f) const {
    return grids_[species].visit(box_, r, rc, std::forward<F>(f));
  }
  const SpeciesGrid& grid(int species) const { return grids_[species]; }
  const Box& box() const { return box_; }

 private:
  Box box_;
  std::vector<SpeciesGrid> grids_;
  std::vector<std::int32_t> species_;
};

// ---- inline implementation of the hot loop ----------------------------------------------------

template <class F>
bool SpeciesGrid::visit(const Box& box, const Vec3& r, double rc, F&& f) const {
  // Per axis, the cells within reach. When no axis is wrapped whole (the usual case) each visited
  // cell has one periodic image next to r, so the separation is p + shift − r with no rounding;
  // otherwise every cell is visited once and the minimum image is taken per candidate.
  int cells[3][kMaxSpan];
  double shift[3][kMaxSpan];
  int spans[3];
  bool wraps = false;
  const Vec3& L = box.edges();
  for (int k = 0; k < 3; ++k) {
    const int reach = static_cast<int>(std::ceil(rc * inv_h_[k]));
    const int c = std::min(static_cast<int>(r[k] * inv_h_[k]), n_[k] - 1);
    spans[k] = 2 * reach + 1;
    if (spans[k] >= n_[k] || spans[k] > kMaxSpan) {
      wraps = true;
      break;
    }
    for (int a = 0; a < spans[k]; ++a) {
      const int cc = c - reach + a;
      cells[k][a] = cc < 0 ? cc + n_[k] : (cc >= n_[k] ? cc - n_[k] : cc);
      shift[k][a] = cc < 0 ? -L[k] : (cc >= n_[k] ? L[k] : 0.0);
    }
  }
  if (wraps) return visit_all_cells(box, r, rc, std::forward<F>(f));
  // Nearest cells first: most trial moves are rejected, and a rejection ends at the first overlap,
  // which is usually in the query's own cell or a face neighbour.
  for (const auto& [a, b, c] : stencil_order(spans[0], spans[1], spans[2])) {
    const int cell = (cells[0][a] * n_[1] + cells[1][b]) * n_[2] + cells[2][c];
    const Vec3 q(r.x() - shift[0][a], r.y() - shift[1][b], r.z() - shift[2][c]);
    if (scan_cell(cell, q, rc * rc, nullptr, f)) return true;
  }
  return false;
}

template <class F>
bool SpeciesGrid::visit_all_cells(const Box& box, const Vec3& r, double rc, F&& f) const {
  const int cells = n_.prod();
  for (int cell = 0; cell < cells; ++cell)
    if (scan_cell(cell, r, rc * rc, &box, f)) return true;
  return false;
}

template <class F>
[[gnu::always_inline]] inline bool SpeciesGrid::scan_cell(int cell, const Vec3& q, double rc2, const Box* min_image_box, F& f) const {
  const int m = count_[cell];
  if (m == 0) return false;
  const std::size_t base = static_cast<std::size_t>(cell) * capacity_;
  if (m <= kDirectScan && min_image_box == nullptr) {
    // Few slots (dense spheres hold about one per cell): the buffered vector pass costs more than
    // it saves. Same candidates, same order, same separations.
    for (int s = 0; s < m; ++s) {
      const std::size_t k = base + static_cast<std::size_t>(s);
      const Vec3 d(sx_[k] - q.x(), sy_[k] - q.y(), sz_[k] - q.z());
      const double d2 = d.x() * d.x() + d.y() * d.y() + d.z() * d.z();
      if (d2 <= rc2 && f(sid_[k], d, d2)) return true;
    }
    return false;
  }
  // The distances of a chunk of slots go to a buffer on the stack, so that visits from several
  // threads (a Verlet list built in parallel) share nothing.
  constexpr int kChunk = 32;
  double r2[kChunk];
  for (int s0 = 0; s0 < m; s0 += kChunk) {
    const int mm = std::min(kChunk, m - s0);
    const double* px = sx_.data() + base + static_cast<std::size_t>(s0);
    const double* py = sy_.data() + base + static_cast<std::size_t>(s0);
    const double* pz = sz_.data() + base + static_cast<std::size_t>(s0);
    // Distance pass without branches so it vectorises; hits are handled afterwards.
    if (min_image_box == nullptr) {
#pragma omp simd
      for (int s = 0; s < mm; ++s) {
        const double dx = px[s] - q.x(), dy = py[s] - q.y(), dz = pz[s] - q.z();
        r2[s] = dx * dx + dy * dy + dz * dz;
      }
    } else {
      const Vec3& L = min_image_box->edges();
      const Vec3& invL = min_image_box->inverse_edges();
#pragma omp simd
      for (int s = 0; s < mm; ++s) {
        double dx = px[s] - q.x(), dy = py[s] - q.y(), dz = pz[s] - q.z();
        dx -= L.x() * std::nearbyint(dx * invL.x());
        dy -= L.y() * std::nearbyint(dy * invL.y());
        dz -= L.z() * std::nearbyint(dz * invL.z());
        r2[s] = dx * dx + dy * dy + dz * dz;
      }
    }
    // Hits as a bit mask, then visited in slot order: no branch per slot to mispredict (about one
    // slot in ten is a hit for boards, whose cells are sized by their length).
    std::uint32_t hits = 0;
    for (int s = 0; s < mm; ++s) hits |= static_cast<std::uint32_t>(r2[s] <= rc2) << s;
    while (hits != 0) {
      const int s = __builtin_ctz(hits);
      hits &= hits - 1;
      Vec3 d(px[s] - q.x(), py[s] - q.y(), pz[s] - q.z());
      if (min_image_box != nullptr) d = min_image_box->min_image(d);
      if (f(sid_[base + static_cast<std::size_t>(s0 + s)], d, r2[s])) return true;
    }
  }
  return false;
}

}  // namespace anisodyn

#pragma once
// Neighbour pairs within a cut-off in a periodic orthorhombic box, at the minimum image (spec 50
// §0), through cell lists: the one pair search of the analysis stages (g(r) and its directional
// forms, the dipolar bonds and chains, the chain mask of the cube order, the nematic clusters, the
// nearest neighbours and the Eps-neighbourhoods of the DBSCAN calibration; the last in a plane with
// open boundaries, planar_candidate_pairs).
//
// Cells: every axis is cut into equal cells no thinner than a quarter of the cut-off, of the width
// that makes the least estimated work (fine in a dense system, about the cut-off in a dilute one,
// never more than a few cells per point). A cell is paired with the cells whose nearest points are
// closer than the cut-off, each pair of cells once. An axis too short for 2m + 1 distinct cells
// within reach m (a cut-off near or beyond a third of the edge) pairs every cell with each of its
// cells once instead, so any cut-off is exact, also one beyond half the box: every pair is then
// still met once, at its minimum image.
//
// Why not the engine's SpeciesGrid (neighbors/cell_list.hpp): it answers one query at a time, as
// MC trial moves need. An all-pairs sweep through it meets every pair twice; its separations
// p + shift − q round differently from the minimum image r_j − r_i that the g(r) histograms are
// built on (a pair on a bin edge could change bins); and once the reach spans the box, as at the
// default g(r) range r_max = L/2, it scans every cell for every query with a nearbyint per
// candidate: twice the work of the plain O(N²) loop. Here each pair of cells is met once and every
// pair's separation is the same expression, so the pairs and separations are bit for bit those of
// the O(N²) loop over wrapped coordinates.
#include <cstddef>
#include <utility>
#include <vector>

#include "anisodyn/core/box.hpp"
#include "anisodyn/core/types.hpp"

namespace anisodyn::analysis {

/// Points wrapped into the box (x − L⌊x/L⌋) and sorted by cell, for one PairGrid.
struct CellSortedPoints {
  std::vector<double> x, y, z;      // wrapped coordinates, cell by cell
  std::vector<std::size_t> index;   // each point's position in the caller's list
  std::vector<std::size_t> first;   // the points of cell c are first[c] … first[c + 1] − 1
};

/// Minimum image of the difference of two coordinates wrapped into [0, L]: one shift suffices.
/// Branch-free, because random separations would defeat branch prediction. Odd in d, bit for bit.
inline double nearest_image(double d, double l, double half) {
  return d - l * static_cast<double>(d > half) + l * static_cast<double>(d < -half);
}

/// A cell's neighbour at (x, y, z) cells along the axes (periodic).
struct CellOffset {
  int x, y, z;
};

class PairGrid {
 public:
  /// Cells for pairs closer than `cutoff` in a box with edges `box_edges` holding about
  /// `particles` points (the sizes of both sets for unlike pairs).
  PairGrid(const Vec3& box_edges, double cutoff, std::size_t particles);

  CellSortedPoints sort(const std::vector<Vec3>& positions) const;

  /// f(i, j, d, r2) for every pair i < j of `p` with r2 = |d|² < cutoff², d = r_j − r_i at the
  /// minimum image (i, j: positions in the list given to sort()).
  template <class F>
  void for_each_pair(const CellSortedPoints& p, F&& f) const {
    sweep(p, p, true, f);
  }
  /// The same for every i of `a` and j of `b` (two different sets: each (i, j) once).
  template <class F>
  void for_each_pair(const CellSortedPoints& a, const CellSortedPoints& b, F&& f) const {
    sweep(a, b, false, f);
  }

  const Int3& cells() const { return n_; }

 private:
  int cell(int cx, int cy, int cz) const { return (cx * n_.y() + cy) * n_.z() + cz; }
  static int periodic(int c, int n) { return c >= n ? c - n : (c < 0 ? c + n : c); }

  template <class F>
  void sweep(const CellSortedPoints& a, const CellSortedPoints& b, bool same, F& f) const;
  template <class F>
  void scan_cells(const CellSortedPoints& a, std::size_t ca, const CellSortedPoints& b, std::size_t cb, bool same, F& f) const;

  Vec3 L_, half_, inv_width_;
  double cutoff2_ = 0.0;
  Int3 n_ = Int3::Ones();
  std::vector<CellOffset> stencil_;
};

/// A point of a plane (the (r_∥, r_⊥) points of the DBSCAN calibration).
struct Point2 {
  double x = 0.0, y = 0.0;
};

/// The pairs i < j of plane points (open boundaries) closer than `reach`, in the order of the cell
/// sweep, which is the same for the same points. The distances are measured on the points shifted to
/// the origin, so they may round differently in the last bit from the caller's own: a caller with an
/// exact criterion reaches a little farther and tests the candidates on its own coordinates.
std::vector<std::pair<std::size_t, std::size_t>> planar_candidate_pairs(const std::vector<Point2>& points, double reach);

struct ClosePair {
  std::size_t i = 0, j = 0;  // i < j, indices into the position list
  Vec3 d;                    // r_j − r_i, minimum image
};

/// Every pair with |r_j − r_i| < cutoff (minimum image); positions need not be wrapped. Pairs are
/// ordered by i, then j.
std::vector<ClosePair> close_pairs(const std::vector<Vec3>& positions, const Box& box, double cutoff);

// ---- inline implementation of the sweep ---------------------------------------------------------

template <class F>
void PairGrid::sweep(const CellSortedPoints& a, const CellSortedPoints& b, bool same, F& f) const {
  if (!(cutoff2_ > 0)) return;
  for (int cx = 0; cx < n_.x(); ++cx)
    for (int cy = 0; cy < n_.y(); ++cy)
      for (int cz = 0; cz < n_.z(); ++cz) {
        const auto ca = static_cast<std::size_t>(cell(cx, cy, cz));
        if (a.first[ca] == a.first[ca + 1]) continue;
        for (const CellOffset& o : stencil_) {
          const auto cb = static_cast<std::size_t>(cell(periodic(cx + o.x, n_.x()), periodic(cy + o.y, n_.y()), periodic(cz + o.z, n_.z())));
          if (same && cb < ca) continue;  // a pair of cells is met from its lower cell
          scan_cells(a, ca, b, cb, same, f);
        }
      }
}

template <class F>
void PairGrid::scan_cells(const CellSortedPoints& a, std::size_t ca, const CellSortedPoints& b, std::size_t cb, bool same,
                          F& f) const {
  const bool one_cell = same && ca == cb;
  const double lx = L_.x(), ly = L_.y(), lz = L_.z(), hx = half_.x(), hy = half_.y(), hz = half_.z();
  for (std::size_t s = a.first[ca]; s < a.first[ca + 1]; ++s) {
    const double xi = a.x[s], yi = a.y[s], zi = a.z[s];
    for (std::size_t u = one_cell ? s + 1 : b.first[cb]; u < b.first[cb + 1]; ++u) {
      const double dx = nearest_image(b.x[u] - xi, lx, hx), dy = nearest_image(b.y[u] - yi, ly, hy),
                   dz = nearest_image(b.z[u] - zi, lz, hz);
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (!(r2 < cutoff2_)) continue;
      // like pairs are reported as i < j with d = r_j − r_i; the negation is exact
      if (same && a.index[s] > b.index[u]) f(b.index[u], a.index[s], Vec3(-dx, -dy, -dz), r2);
      else f(a.index[s], b.index[u], Vec3(dx, dy, dz), r2);
    }
  }
}

}  // namespace anisodyn::analysis

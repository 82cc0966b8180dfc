#include "anisodyn/analysis/pair_search.hpp"

#include <algorithm>
#include <cmath>

namespace anisodyn::analysis {

namespace {

/// The work of a cell pair besides its candidates (loop set-up, the cell index), in units of one
/// candidate's distance test; and the extra work of a candidate whose test r < r_c cannot be
/// predicted (a cell pair with half its candidates within the cut-off: the branch mispredicts half
/// the time, which made one cell over a whole box twice as slow as 7³ cells at the g(r) default
/// r_max = L/2). Chosen so that the widths picked are the fastest measured by
/// bench/analysis_pair_structure.cpp in its dense (r_max = L/2) and dilute (r_max = 5σ, bonds) cases.
constexpr double kCellPairCost = 2.0;
constexpr double kMispredictionCost = 5.0;
/// Cells no thinner than cutoff / kFinestDivision: finer cells trim the stencil's corners only a
/// little more, at the price of many more cell pairs.
constexpr double kFinestDivision = 4.0;
/// At most this many cells per point, whatever the cut-off: the sweep visits every cell.
constexpr double kMaxCellsPerPoint = 4.0;

/// Cells per axis for cells no thinner than `width`.
Int3 cells_for_width(const Vec3& L, double width) {
  Int3 n;
  for (int a = 0; a < 3; ++a) n[a] = static_cast<int>(std::clamp(std::floor(L[a] / width), 1.0, 1e6));
  return n;
}

/// Cell offsets along one axis with the least and the largest distance between points of two cells
/// that far apart on the periodic axis: with n cells of width w, k = min(o mod n, n − o mod n) cells
/// apart, (k − 1) w and min((k + 1) w, L/2). The offsets are −m … m for a reach of m cells when they
/// are 2m + 1 distinct cells, else every cell once (0 … n − 1).
struct AxisOffsets {
  std::vector<int> offset;
  std::vector<double> near, far;
};

AxisOffsets axis_offsets(int n, double edge, double reach) {
  AxisOffsets out;
  const double width = edge / n;
  const int m = static_cast<int>(std::floor(reach / width)) + 1;  // m·w > reach
  const bool wraps = 2 * m + 1 > n;
  for (int o = wraps ? 0 : -m; o <= (wraps ? n - 1 : m); ++o) {
    const int residue = ((o % n) + n) % n, k = std::min(residue, n - residue);
    out.offset.push_back(o);
    out.near.push_back(std::max(0, k - 1) * width);
    out.far.push_back(std::min((k + 1) * width, edge / 2));
  }
  return out;
}

/// Calls f(offset, within) for the cell offsets whose nearest points are within reach; `within`
/// estimates the share of their candidates within reach: of the separations at the quarter and
/// three-quarter points of each axis's range [least, largest distance], the share within reach.
template <class F>
void for_each_stencil_cell(const Int3& n, const Vec3& L, double reach, F&& f) {
  AxisOffsets axis[3];
  for (int a = 0; a < 3; ++a) axis[a] = axis_offsets(n[a], L[a], reach);
  auto sq = [](double x) { return x * x; };
  auto at = [&](int a, std::size_t i, double q) { return sq(axis[a].near[i] + q * (axis[a].far[i] - axis[a].near[i])); };
  for (std::size_t i = 0; i < axis[0].offset.size(); ++i)
    for (std::size_t j = 0; j < axis[1].offset.size(); ++j)
      for (std::size_t k = 0; k < axis[2].offset.size(); ++k) {
        if (at(0, i, 0) + at(1, j, 0) + at(2, k, 0) >= reach * reach) continue;
        double within = 0;
        for (double qx : {0.25, 0.75})
          for (double qy : {0.25, 0.75})
            for (double qz : {0.25, 0.75}) within += at(0, i, qx) + at(1, j, qy) + at(2, k, qz) < reach * reach ? 0.125 : 0.0;
        f(CellOffset{axis[0].offset[i], axis[1].offset[j], axis[2].offset[k]}, within);
      }
}

/// Estimated work per point of the sweep over cells n: Σ over the stencil of kCellPairCost plus the
/// points expected in a cell, each dearer by kMispredictionCost · 2 min(p, 1 − p), p the share of
/// them within reach.
double estimated_work(const Int3& n, const Vec3& L, double reach, double density) {
  const double per_cell = density * L.prod() / n.prod();
  double work = 0;
  for_each_stencil_cell(n, L, reach, [&](const CellOffset&, double within) {
    work += kCellPairCost + per_cell * (1 + kMispredictionCost * 2 * std::min(within, 1 - within));
  });
  return work;
}

/// Cells for a cut-off: of the widths from cutoff / kFinestDivision (or the width of
/// kMaxCellsPerPoint cells per point) upwards in steps of 10 %, the one with the least estimated
/// work. Fine cells suit a dense system (few far candidates), cells about the cut-off wide a dilute
/// one (few cell pairs).
Int3 choose_cells(const Vec3& L, double cutoff, double reach, std::size_t particles) {
  const double points = std::max<double>(1.0, static_cast<double>(particles)), density = points / L.prod();
  // slightly wider than cutoff / 4, so that the reach is not one cell longer by a rounding
  double width = std::max(cutoff / kFinestDivision * (1 + 1e-6), std::cbrt(L.prod() / (kMaxCellsPerPoint * points)));
  Int3 best = Int3::Ones();
  double best_work = INFINITY;
  for (;; width *= 1.1) {
    const Int3 n = cells_for_width(L, width);
    const double work = estimated_work(n, L, reach, density);
    if (work < best_work) {
      best_work = work;
      best = n;
    }
    if (n == Int3::Ones()) return best;
  }
}

}  // namespace

PairGrid::PairGrid(const Vec3& box_edges, double cutoff, std::size_t particles) : L_(box_edges), half_(box_edges / 2) {
  if (!(cutoff > 0)) return;  // no pairs
  cutoff2_ = cutoff * cutoff;
  // Rounding can put a point one ulp into the neighbouring cell: the reach and the pruning keep a
  // margin far above it.
  const double reach = cutoff + 1e-9 * (cutoff + L_.maxCoeff());
  n_ = choose_cells(L_, cutoff, reach, particles);
  for (int a = 0; a < 3; ++a) inv_width_[a] = n_[a] / L_[a];
  for_each_stencil_cell(n_, L_, reach, [&](const CellOffset& o, double) { stencil_.push_back(o); });
}

CellSortedPoints PairGrid::sort(const std::vector<Vec3>& positions) const {
  const std::size_t n = positions.size(), cells = static_cast<std::size_t>(n_.prod());
  std::vector<double> w(3 * n);
  std::vector<std::size_t> cell_of(n);
  for (std::size_t i = 0; i < n; ++i) {
    int c[3];
    for (int a = 0; a < 3; ++a) {
      const double x = positions[i][a] - L_[a] * std::floor(positions[i][a] / L_[a]);
      w[3 * i + static_cast<std::size_t>(a)] = x;
      // x can round to L (or to −0 … −ulp): clamp into the first and last cells
      c[a] = std::clamp(static_cast<int>(x * inv_width_[a]), 0, n_[a] - 1);
    }
    cell_of[i] = static_cast<std::size_t>(cell(c[0], c[1], c[2]));
  }
  CellSortedPoints p;
  p.first.assign(cells + 1, 0);
  for (std::size_t c : cell_of) ++p.first[c + 1];
  for (std::size_t c = 0; c < cells; ++c) p.first[c + 1] += p.first[c];
  p.x.resize(n);
  p.y.resize(n);
  p.z.resize(n);
  p.index.resize(n);
  std::vector<std::size_t> next(p.first.begin(), p.first.end() - 1);
  for (std::size_t i = 0; i < n; ++i) {  // stable: ascending index within a cell
    const std::size_t s = next[cell_of[i]]++;
    p.x[s] = w[3 * i];
    p.y[s] = w[3 * i + 1];
    p.z[s] = w[3 * i + 2];
    p.index[s] = i;
  }
  return p;
}

std::vector<std::pair<std::size_t, std::size_t>> planar_candidate_pairs(const std::vector<Point2>& p, double reach) {
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  if (p.size() < 2 || !(reach > 0)) return pairs;
  double x0 = p.front().x, x1 = x0, y0 = p.front().y, y1 = y0;
  for (const auto& q : p) {
    x0 = std::min(x0, q.x); x1 = std::max(x1, q.x);
    y0 = std::min(y0, q.y); y1 = std::max(y1, q.y);
  }
  // The points lie in the z = 0 plane of a periodic box more than twice their spread plus the reach
  // on each axis, so no periodic image comes within reach; a thin third axis keeps one layer of cells.
  const Vec3 box(2 * (x1 - x0 + reach), 2 * (y1 - y0 + reach), reach / 4);
  std::vector<Vec3> r(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) r[i] = Vec3(p[i].x - x0, p[i].y - y0, 0.0);
  const PairGrid grid(box, reach, p.size());
  grid.for_each_pair(grid.sort(r), [&](std::size_t i, std::size_t j, const Vec3&, double) { pairs.emplace_back(i, j); });
  return pairs;
}

std::vector<ClosePair> close_pairs(const std::vector<Vec3>& positions, const Box& box, double cutoff) {
  std::vector<ClosePair> pairs;
  if (positions.size() < 2 || !(cutoff > 0)) return pairs;
  const PairGrid grid(box.edges(), cutoff, positions.size());
  grid.for_each_pair(grid.sort(positions), [&](std::size_t i, std::size_t j, const Vec3& d, double) { pairs.push_back({i, j, d}); });
  std::sort(pairs.begin(), pairs.end(), [](const ClosePair& a, const ClosePair& b) { return a.i != b.i ? a.i < b.i : a.j < b.j; });
  return pairs;
}

}  // namespace anisodyn::analysis

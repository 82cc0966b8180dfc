#include "anisodyn/neighbors/cell_ordered_pairs.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace anisodyn {

namespace {

/// r wrapped into [0, L) (positions may be unwrapped or a rounding off the edge).
double wrapped(double r, double L, double inv_L) {
  double w = r - L * std::floor(r * inv_L);
  if (w >= L) w -= L;
  if (w < 0.0) w = 0.0;
  return w;
}

}  // namespace

CellOrderedPairs::CellOrderedPairs(double cutoff, double skin) : cutoff_(cutoff), skin_(skin) {
  if (!(cutoff > 0.0) || !(skin > 0.0)) throw std::invalid_argument("CellOrderedPairs: expected a positive cut-off and skin");
}

bool CellOrderedPairs::update(const Box& box, const double* x, const double* y, const double* z, std::size_t n) {
  bool stale = built_x_.size() != n || box.edges() != box_.edges();
  if (!stale) {
    // Every step looks at every particle: in parallel (a serial loop here was 6% of a two-thread step).
    const double limit2 = 0.25 * skin_ * skin_;
    int moved = 0;
#pragma omp parallel for schedule(static) reduction(| : moved)
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 d = box.min_image(Vec3(x[i] - built_x_[i], y[i] - built_y_[i], z[i] - built_z_[i]));
      moved |= d.squaredNorm() > limit2 ? 1 : 0;
    }
    stale = moved != 0;
  }
  if (stale) build(box, x, y, z, n);
  return stale;
}

void CellOrderedPairs::rebuild_at(const Box& box, const std::vector<double>& positions) {
  const std::size_t n = positions.size() / 3;
  std::vector<double> x(n), y(n), z(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = positions[3 * i];
    y[i] = positions[3 * i + 1];
    z[i] = positions[3 * i + 2];
  }
  build(box, x.data(), y.data(), z.data(), n);
}

std::vector<double> CellOrderedPairs::built_positions() const {
  std::vector<double> out;
  out.reserve(3 * built_x_.size());
  for (std::size_t i = 0; i < built_x_.size(); ++i) out.insert(out.end(), {built_x_[i], built_y_[i], built_z_[i]});
  return out;
}

void CellOrderedPairs::build(const Box& box, const double* x, const double* y, const double* z, std::size_t n) {
  if (!(box.shortest_edge() >= 2.0 * (cutoff_ + skin_)))
    throw std::invalid_argument("CellOrderedPairs: the box must be at least twice the cut-off plus the skin along every edge");
  box_ = box;
  built_x_.assign(x, x + n);
  built_y_.assign(y, y + n);
  built_z_.assign(z, z + n);
  sort_into_cells(box, x, y, z, n);
  find_pairs(box);
  list_lower_pairs();
  ++builds_;
}

void CellOrderedPairs::sort_into_cells(const Box& box, const double* x, const double* y, const double* z, std::size_t n) {
  const Vec3 L = box.edges(), inv = box.inverse_edges();
  const double reach = cutoff_ + skin_;
  Int3 cells;
  for (int a = 0; a < 3; ++a) cells[a] = std::max(1, static_cast<int>(std::floor(L[a] / reach)));
  const int ncells = cells.prod();
  if (cells != cells_) {
    // Each cell's distinct neighbours (a box of 2 cells along an edge has the same cell at −1 and +1)
    // above it, ascending: the cells the search of a particle of that cell visits besides its own.
    cells_ = cells;
    search_runs_.assign(static_cast<std::size_t>(ncells), {});
    std::vector<std::int32_t> up;
    for (int c = 0; c < ncells; ++c) {
      const int cx = c % cells[0], cy = (c / cells[0]) % cells[1], cz = c / (cells[0] * cells[1]);
      up.assign(1, c);  // the cell itself first (its search starts after the particle)
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = (cx + dx + cells[0]) % cells[0], ny = (cy + dy + cells[1]) % cells[1], nz = (cz + dz + cells[2]) % cells[2];
            const int nc = nx + cells[0] * (ny + cells[1] * nz);
            if (nc > c) up.push_back(nc);
          }
      std::sort(up.begin(), up.end());
      up.erase(std::unique(up.begin(), up.end()), up.end());
      auto& runs = search_runs_[static_cast<std::size_t>(c)];
      for (const std::int32_t nc : up) {
        if (!runs.empty() && runs.back().second + 1 == nc) runs.back().second = nc;
        else runs.emplace_back(nc, nc);
      }
    }
  }
  std::vector<std::int32_t> cell(n);
  std::vector<double> wx(n), wy(n), wz(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    wx[i] = wrapped(x[i], L.x(), inv.x());
    wy[i] = wrapped(y[i], L.y(), inv.y());
    wz[i] = wrapped(z[i], L.z(), inv.z());
    const int cx = std::min(cells[0] - 1, static_cast<int>(wx[i] * cells[0] * inv.x()));
    const int cy = std::min(cells[1] - 1, static_cast<int>(wy[i] * cells[1] * inv.y()));
    const int cz = std::min(cells[2] - 1, static_cast<int>(wz[i] * cells[2] * inv.z()));
    cell[i] = cx + cells[0] * (cy + cells[1] * cz);
  }
  // Counting sort, stable: within a cell, particles keep their index order.
  cell_start_.assign(static_cast<std::size_t>(ncells) + 1, 0);
  for (const std::int32_t c : cell) ++cell_start_[static_cast<std::size_t>(c) + 1];
  for (int c = 0; c < ncells; ++c) cell_start_[static_cast<std::size_t>(c) + 1] += cell_start_[static_cast<std::size_t>(c)];
  std::vector<std::int32_t> next(cell_start_.begin(), cell_start_.end() - 1);
  order_.resize(n);
  position_of_.resize(n);
  cell_of_.resize(n);
  sx_.resize(n);
  sy_.resize(n);
  sz_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(next[static_cast<std::size_t>(cell[i])]++);
    order_[k] = static_cast<std::int32_t>(i);
    position_of_[i] = static_cast<std::int32_t>(k);
    cell_of_[k] = cell[i];
    sx_[k] = wx[i];
    sy_[k] = wy[i];
    sz_[k] = wz[i];
  }
}

std::vector<std::size_t> CellOrderedPairs::scan_blocks(int blocks) const {
  // A cell's rows scan the rest of their own cell and the cells of its runs. The cells of the
  // first layers have many more cells above them (their neighbours across the periodic boundary)
  // than those of the last: blocks of equal numbers of rows would leave the first block with
  // the most work.
  const std::size_t cells = search_runs_.size(), n = order_.size();
  std::vector<double> work(cells + 1, 0.0);  // prefix sums over the cells
  for (std::size_t c = 0; c < cells; ++c) {
    const auto size = static_cast<double>(cell_start_[c + 1] - cell_start_[c]);
    double scanned = 0.0;
    for (const auto& [first, last] : search_runs_[c])
      scanned += static_cast<double>(cell_start_[static_cast<std::size_t>(last) + 1] - cell_start_[static_cast<std::size_t>(first)]);
    work[c + 1] = work[c] + size * (scanned - 0.5 * (size + 1.0));
  }
  std::vector<std::size_t> bound(static_cast<std::size_t>(blocks) + 1, n);
  bound[0] = 0;
  for (int b = 1; b < blocks; ++b) {
    const double target = work[cells] * b / blocks;
    const auto c = static_cast<std::size_t>(std::lower_bound(work.begin(), work.end(), target) - work.begin());
    bound[static_cast<std::size_t>(b)] = std::max(bound[static_cast<std::size_t>(b) - 1], static_cast<std::size_t>(cell_start_[std::min(c, cells)]));
  }
  return bound;
}

void CellOrderedPairs::find_pairs(const Box& box) {
  const std::size_t n = order_.size();
  const Vec3 L = box.edges(), inv = box.inverse_edges();
  const double reach2 = (cutoff_ + skin_) * (cutoff_ + skin_);
  // Each thread lists the rows of a contiguous block of positions into its own buffer; the blocks
  // are joined in order, so the list is the same for any thread count.
  int blocks = 1;
#ifdef _OPENMP
  blocks = omp_get_max_threads();
#endif
  // Per block: its pairs, in a buffer kept from build to build (it only grows), and their count.
  found_.resize(std::max(found_.size(), static_cast<std::size_t>(blocks)));
  std::vector<std::size_t> found_count(static_cast<std::size_t>(blocks), 0);
  std::vector<std::size_t> row_end(n);
  const std::vector<std::size_t> bound = scan_blocks(blocks);
#pragma omp parallel for schedule(static, 1) num_threads(blocks)
  for (int b = 0; b < blocks; ++b) {
    const std::size_t begin = bound[static_cast<std::size_t>(b)], end = bound[static_cast<std::size_t>(b) + 1];
    // The pairs are written at `count` and kept by advancing it: no branch on the distance, which
    // is as often in reach as not.
    std::vector<std::int32_t>& mine = found_[static_cast<std::size_t>(b)];
    if (mine.size() < (end - begin) * 16 + 1024) mine.resize((end - begin) * 32 + 1024);
    std::size_t count = 0;
    constexpr std::size_t kBatch = 64;
    double r2[kBatch];
    for (std::size_t k = begin; k < end; ++k) {
      const double xk = sx_[k], yk = sy_[k], zk = sz_[k];
      auto scan = [&](std::size_t from, std::size_t to) {
        for (std::size_t first = from; first < to; first += kBatch) {
          const std::size_t batch = std::min(kBatch, to - first);
          for (std::size_t c = 0; c < batch; ++c) {
            double dx = sx_[first + c] - xk, dy = sy_[first + c] - yk, dz = sz_[first + c] - zk;
            dx -= L.x() * std::nearbyint(dx * inv.x());
            dy -= L.y() * std::nearbyint(dy * inv.y());
            dz -= L.z() * std::nearbyint(dz * inv.z());
            r2[c] = dx * dx + dy * dy + dz * dz;
          }
          if (count + batch > mine.size()) mine.resize(2 * mine.size() + batch);
          std::int32_t* out = mine.data();
          for (std::size_t c = 0; c < batch; ++c) {
            out[count] = static_cast<std::int32_t>(first + c);
            count += r2[c] < reach2 ? 1 : 0;
          }
        }
      };
      const auto c = static_cast<std::size_t>(cell_of_[k]);
      const auto& runs = search_runs_[c];  // the first run begins with the particle's own cell
      scan(k + 1, static_cast<std::size_t>(cell_start_[static_cast<std::size_t>(runs.front().second) + 1]));
      for (std::size_t r = 1; r < runs.size(); ++r)
        scan(static_cast<std::size_t>(cell_start_[static_cast<std::size_t>(runs[r].first)]),
             static_cast<std::size_t>(cell_start_[static_cast<std::size_t>(runs[r].second) + 1]));
      row_end[k] = count;  // within the block, for now
    }
    found_count[static_cast<std::size_t>(b)] = count;
  }
  first_pair_.assign(n + 1, 0);
  partners_.clear();
  for (int b = 0; b < blocks; ++b) {
    const std::size_t offset = partners_.size();
    const std::size_t begin = bound[static_cast<std::size_t>(b)], end = bound[static_cast<std::size_t>(b) + 1];
    for (std::size_t k = begin; k < end; ++k) first_pair_[k + 1] = row_end[k] + offset;
    const auto& mine = found_[static_cast<std::size_t>(b)];
    partners_.insert(partners_.end(), mine.begin(), mine.begin() + static_cast<std::ptrdiff_t>(found_count[static_cast<std::size_t>(b)]));
  }
}

void CellOrderedPairs::list_lower_pairs() {
  // A counting sort of the pair slots by upper position, in parallel. Each thread counts the upper
  // positions of the pairs of its own rows (a histogram of its own); the histograms are turned into
  // places, position by position in thread order; then each thread puts its slots at its places.
  // The rows of thread t precede those of t + 1, so each position's slots come out ascending: the
  // same list as one thread's, and each thread reads only its share of the pairs.
  const std::size_t n = order_.size(), pairs = partners_.size();
  lower_start_.resize(n + 1);
  lower_.resize(pairs);
  const std::int32_t* partner = partners_.data();
  std::size_t max_threads = 1;
#ifdef _OPENMP
  max_threads = static_cast<std::size_t>(omp_get_max_threads());
#endif
  lower_place_.assign(max_threads * n, 0);
  std::vector<std::size_t> range_total(max_threads + 1, 0);
#pragma omp parallel num_threads(static_cast<int>(max_threads))
  {
    std::size_t threads = 1, t = 0;
#ifdef _OPENMP
    threads = static_cast<std::size_t>(omp_get_num_threads());
    t = static_cast<std::size_t>(omp_get_thread_num());
#endif
    // Rows split by pairs (the first rows have more); positions split evenly for the places.
    const auto first_row = [&](std::size_t u) {
      const auto it = std::lower_bound(first_pair_.begin(), first_pair_.end() - 1, pairs * u / threads);
      return static_cast<std::size_t>(it - first_pair_.begin());
    };
    const std::size_t row_lo = first_row(t), row_hi = t + 1 == threads ? n : first_row(t + 1);
    const std::size_t pos_lo = n * t / threads, pos_hi = n * (t + 1) / threads;
    std::size_t* mine = lower_place_.data() + t * n;
    for (std::size_t s = first_pair_[row_lo]; s < first_pair_[row_hi]; ++s) ++mine[partner[s]];
#pragma omp barrier
    std::size_t total = 0;
    for (std::size_t k = pos_lo; k < pos_hi; ++k)
      for (std::size_t u = 0; u < threads; ++u) total += lower_place_[u * n + k];
    range_total[t + 1] = total;
#pragma omp barrier
    std::size_t place = 0;
    for (std::size_t u = 0; u <= t; ++u) place += range_total[u];
    for (std::size_t k = pos_lo; k < pos_hi; ++k) {
      lower_start_[k] = place;
      for (std::size_t u = 0; u < threads; ++u) {
        std::size_t& count = lower_place_[u * n + k];
        const std::size_t c = count;
        count = place;
        place += c;
      }
    }
    if (t + 1 == threads) lower_start_[n] = place;
#pragma omp barrier
    for (std::size_t k = row_lo; k < row_hi; ++k)
      for (std::size_t s = first_pair_[k]; s < first_pair_[k + 1]; ++s) lower_[mine[partner[s]]++] = static_cast<std::int32_t>(s);
  }
}

}  // namespace anisodyn

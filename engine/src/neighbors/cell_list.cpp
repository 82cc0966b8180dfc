#include "anisodyn/neighbors/cell_list.hpp"

#include <limits>
#include <memory>
#include <utility>

namespace anisodyn {

namespace {
// Cells per particle above which a grid stops refining: beyond it most cells are empty and
// queries with long reach pay for visiting them.
constexpr double kMaxCellsPerParticle = 2.0;
// Position of an empty slot: NaN fails every distance comparison, so short cells can be scanned
// without reading their count.
constexpr double kEmptySlot = std::numeric_limits<double>::quiet_NaN();
}  // namespace

const std::vector<StencilCell>& stencil_order(int sx, int sy, int sz) {
  // Cached per thread and per shape: an engine's queries use a few spans that interleave (trial
  // queries of each species pair, skin-list searches with a longer reach), and re-sorting a
  // stencil on every change of span cost 4% of a mixture's DMC run.
  struct Entry {
    int sx, sy, sz;
    std::vector<StencilCell> order;
  };
  thread_local std::vector<std::unique_ptr<Entry>> cache;
  thread_local Entry* last = nullptr;
  if (last != nullptr && last->sx == sx && last->sy == sy && last->sz == sz) return last->order;
  for (const auto& e : cache)
    if (e->sx == sx && e->sy == sy && e->sz == sz) return (last = e.get())->order;
  auto entry = std::make_unique<Entry>(Entry{sx, sy, sz, {}});
  auto& order = entry->order;
  for (int a = 0; a < sx; ++a)
    for (int b = 0; b < sy; ++b)
      for (int c = 0; c < sz; ++c)
        order.push_back({static_cast<std::int8_t>(a), static_cast<std::int8_t>(b), static_cast<std::int8_t>(c)});
  auto d2 = [&](const StencilCell& s) {
    const int da = 2 * s.a - (sx - 1), db = 2 * s.b - (sy - 1), dc = 2 * s.c - (sz - 1);
    return da * da + db * db + dc * dc;
  };
  std::stable_sort(order.begin(), order.end(), [&](const StencilCell& x, const StencilCell& y) { return d2(x) < d2(y); });
  cache.push_back(std::move(entry));
  return (last = cache.back().get())->order;
}

void SpeciesGrid::configure(const Box& box, double self_cutoff, std::size_t count) {
  const Vec3& L = box.edges();
  const Int3 previous_cells = n_;
  double h = std::max(self_cutoff, 1e-12);
  const double max_cells = std::max(1.0, kMaxCellsPerParticle * static_cast<double>(count));
  for (;;) {
    for (int k = 0; k < 3; ++k) n_[k] = std::max(1, static_cast<int>(std::floor(L[k] / h)));
    if (static_cast<double>(n_.cast<double>().prod()) <= max_cells) break;
    h *= 1.1;
  }
  for (int k = 0; k < 3; ++k) {
    h_[k] = L[k] / n_[k];
    inv_h_[k] = 1.0 / h_[k];
  }
  const double mean_occupancy = static_cast<double>(count) / n_.cast<double>().prod();
  const std::size_t wanted = std::max<std::size_t>(4, static_cast<std::size_t>(std::ceil(3.0 * mean_occupancy)));
  // The same cells keep a capacity they had to grow to: where the particles crowd part of the box
  // (a domain sweep's copy), the estimate from the mean is short, and the storage would regrow by
  // doubling at every rebuild. The slots' order, and so every result, is the same either way.
  capacity_ = n_ == previous_cells ? std::max(wanted, capacity_) : wanted;
}

void SpeciesGrid::leave_empty() {
  count_.clear();
  pos_.clear();
  sid_.clear();
}

void SpeciesGrid::clear() {
  const std::size_t cells = static_cast<std::size_t>(n_.prod());
  count_.assign(cells, 0);
  pos_.assign(3 * cells * capacity_, kEmptySlot);
  sid_.assign(cells * capacity_, -1);
  cell_.assign(cell_.size(), -1);  // assign keeps the memory: domain sweeps rebuild every cycle
  slot_.assign(slot_.size(), -1);
}

int SpeciesGrid::cell_of(const Vec3& r) const {
  int c[3];
  for (int k = 0; k < 3; ++k) c[k] = std::clamp(static_cast<int>(r[k] * inv_h_[k]), 0, n_[k] - 1);
  return (c[0] * n_[1] + c[1]) * n_[2] + c[2];
}

void SpeciesGrid::place(std::int32_t particle, int cell, const Vec3& r) {
  if (static_cast<std::size_t>(count_[cell]) == capacity_) grow_capacity();
  const std::size_t slot = static_cast<std::size_t>(count_[cell]++);
  store(x_index(cell, slot), r);
  sid_[static_cast<std::size_t>(cell) * capacity_ + slot] = particle;
  if (cell_.size() <= static_cast<std::size_t>(particle)) {
    cell_.resize(static_cast<std::size_t>(particle) + 1, -1);
    slot_.resize(static_cast<std::size_t>(particle) + 1, -1);
  }
  cell_[particle] = cell;
  slot_[particle] = static_cast<std::int32_t>(slot);
}

void SpeciesGrid::insert(std::int32_t particle, const Vec3& r) { place(particle, cell_of(r), r); }

void SpeciesGrid::remove(std::int32_t particle) {
  const int cell = cell_[particle];
  const std::size_t base = static_cast<std::size_t>(cell) * capacity_;
  const std::size_t slot = static_cast<std::size_t>(slot_[particle]);
  const std::size_t last = static_cast<std::size_t>(--count_[cell]);
  if (slot != last) {  // fill the hole with the cell's last entry
    store(x_index(cell, slot), stored(x_index(cell, last)));
    sid_[base + slot] = sid_[base + last];
    slot_[sid_[base + slot]] = static_cast<std::int32_t>(slot);
  }
  store(x_index(cell, last), Vec3::Constant(kEmptySlot));
  cell_[particle] = -1;
}

void SpeciesGrid::move(std::int32_t particle, const Vec3& r) {
  const int cell = cell_of(r);
  if (cell == cell_[particle]) {
    store(x_index(cell, static_cast<std::size_t>(slot_[particle])), r);
    return;
  }
  remove(particle);
  place(particle, cell, r);
}

void SpeciesGrid::grow_capacity() {
  const std::size_t old_cap = capacity_, cells = count_.size();
  const std::vector<double> old_pos = std::move(pos_);
  const std::vector<std::int32_t> old_id = std::move(sid_);
  capacity_ *= 2;
  pos_.assign(3 * cells * capacity_, kEmptySlot);
  sid_.assign(cells * capacity_, -1);
  for (std::size_t c = 0; c < cells; ++c)
    for (std::size_t s = 0; s < static_cast<std::size_t>(count_[c]); ++s) {
      const std::size_t from = 3 * c * old_cap + s;
      store(x_index(static_cast<int>(c), s), Vec3(old_pos[from], old_pos[from + old_cap], old_pos[from + 2 * old_cap]));
      sid_[c * capacity_ + s] = old_id[c * old_cap + s];
    }
}

void CellList::build(const Box& box, const std::vector<double>& x, const std::vector<double>& y,
                     const std::vector<double>& z, const std::vector<std::int32_t>& species,
                     const std::vector<double>& self_cutoffs, const std::vector<std::size_t>& expected_counts) {
  configure(box, species, self_cutoffs, expected_counts);
  fill(x, y, z, std::vector<char>(self_cutoffs.size(), 1));
}

void CellList::configure(const Box& box, const std::vector<std::int32_t>& species, const std::vector<double>& self_cutoffs,
                         const std::vector<std::size_t>& expected_counts) {
  box_ = box;
  species_ = species;
  grids_.resize(self_cutoffs.size());  // fill() resets each grid, reusing its memory
  std::vector<std::size_t> counts(self_cutoffs.size(), 0);
  for (auto s : species) counts[static_cast<std::size_t>(s)]++;
  for (std::size_t s = 0; s < expected_counts.size() && s < counts.size(); ++s) counts[s] = std::max(counts[s], expected_counts[s]);
  for (std::size_t s = 0; s < grids_.size(); ++s) grids_[s].configure(box, self_cutoffs[s], counts[s]);
  filled_.assign(grids_.size(), 0);
}

void CellList::fill(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& z,
                    const std::vector<char>& filled) {
  filled_ = filled;
  for (std::size_t s = 0; s < grids_.size(); ++s) {
    if (filled_[s]) grids_[s].clear();
    else grids_[s].leave_empty();
  }
  for (std::size_t i = 0; i < x.size(); ++i) {
    const auto s = static_cast<std::size_t>(species_[i]);
    if (filled_[s]) grids_[s].insert(static_cast<std::int32_t>(i), Vec3(x[i], y[i], z[i]));
  }
}

void CellList::insert(std::int32_t particle, int species, const Vec3& r) {
  if (species_.size() <= static_cast<std::size_t>(particle)) species_.resize(static_cast<std::size_t>(particle) + 1, -1);
  species_[static_cast<std::size_t>(particle)] = species;
  if (filled(species)) grids_[static_cast<std::size_t>(species)].insert(particle, r);
}

}  // namespace anisodyn

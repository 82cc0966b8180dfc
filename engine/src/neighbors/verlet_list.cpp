#include "anisodyn/neighbors/verlet_list.hpp"

#include <algorithm>
#include <utility>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "anisodyn/geometry/spherocylinder.hpp"
#include "anisodyn/neighbors/cell_list.hpp"

namespace anisodyn {

namespace {
// The skin of the candidates of a list with segments, in units of the list's skin. The candidates
// are searched again once a centre has moved by half of it: twice the skin allows four times as
// many diffusive steps, and centres move less than the ends of long rods (BD rods of spec 20 at
// (L/D)φ = 1.76: once per about 400 steps, the segment list once per 36).
constexpr double kCandidateSkins = 2.0;
// Segment tests accept pairs up to (1 + kRoundOff)(cut-off + skin): computed distances are off by
// about 10⁻¹⁶ of the segment lengths, so round-off can only add pairs, never drop one.
constexpr double kRoundOff = 1e-9;
// The distance of the infinite axes, |d·n|/|n| with n = û_i × û_j, is computed with a relative error
// of about 4ε|d|/(|d·n|) (ε = 2⁻⁵³, the rounding of n); at the reach, |d·n| = reach |n|. Pairs with
// reach² |n|² ≤ kAxesAccurate |d|² (nearly parallel axes) skip that test, which keeps its error
// below 10⁻¹⁰, well inside kRoundOff.
constexpr double kAxesAccurate = 1e-10;
}  // namespace

VerletList::VerletList(std::vector<double> cutoffs, int nspecies, double skin, std::vector<double> half_lengths)
    : cutoffs_(std::move(cutoffs)),
      nspecies_(nspecies),
      skin_(skin),
      half_lengths_(half_lengths.empty() ? std::vector<double>(static_cast<std::size_t>(nspecies), 0.0) : std::move(half_lengths)) {
  if (std::none_of(half_lengths_.begin(), half_lengths_.end(), [](double h) { return h > 0.0; })) return;
  std::vector<double> reach(cutoffs_.size());
  for (int a = 0; a < nspecies_; ++a)
    for (int b = 0; b < nspecies_; ++b)
      reach[static_cast<std::size_t>(a * nspecies_ + b)] = (cutoff(a, b) + skin_) * (1.0 + kRoundOff) + half_length(a) + half_length(b);
  candidates_ = std::make_unique<VerletList>(std::move(reach), nspecies_, kCandidateSkins * skin_);
}

VerletList::VerletList(VerletList&&) noexcept = default;
VerletList& VerletList::operator=(VerletList&&) noexcept = default;
VerletList::~VerletList() = default;

bool VerletList::update(const Box& box, const Particles& p) {
  bool stale = built_at_.size() != p.size() || box.edges() != box_.edges();
  const double limit = 0.5 * skin_;
  for (std::size_t i = 0; !stale && i < p.size(); ++i) {
    double moved = box.min_image(p.position(i) - built_at_[i]).norm();
    if (candidates_) moved += half_length(p.species[i]) * (p.orientation(i) * Vec3::UnitZ() - axis_at_[i]).norm();
    stale = moved > limit;
  }
  if (stale) build(box, p);
  return stale;
}

void VerletList::build(const Box& box, const Particles& p) {
  const std::size_t n = p.size();
  box_ = box;
  built_at_.resize(n);
  for (std::size_t i = 0; i < n; ++i) built_at_[i] = p.position(i);
  // The pairs (i, j > i), by i and then j ascending: pair k is upper[k].
  std::vector<std::int32_t> upper;
  std::vector<std::size_t> upper_end(n);
  if (candidates_) build_from_candidates(box, p, upper, upper_end);
  else build_from_cells(box, p, upper, upper_end);

  // Full rows: the partners below i (ascending, as the pairs come by ascending i), then those above.
  std::vector<std::size_t> lower(n, 0);
  for (const std::int32_t j : upper) ++lower[static_cast<std::size_t>(j)];
  offsets_.assign(n + 1, 0);
  first_pair_.assign(n + 1, 0);
  above_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    first_pair_[i + 1] = upper_end[i];
    above_[i] = offsets_[i] + lower[i];
    offsets_[i + 1] = above_[i] + (upper_end[i] - first_pair_[i]);
  }
  partners_.resize(offsets_[n]);
  pair_slots_.resize(offsets_[n]);
  std::vector<std::size_t> next(offsets_.begin(), offsets_.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = first_pair_[i]; k < upper_end[i]; ++k) {
      const auto j = static_cast<std::size_t>(upper[k]);
      const std::size_t at = above_[i] + (k - first_pair_[i]);
      partners_[at] = upper[k];
      pair_slots_[at] = static_cast<std::int32_t>(k);
      partners_[next[j]] = static_cast<std::int32_t>(i);
      pair_slots_[next[j]++] = static_cast<std::int32_t>(k);
    }
  ++builds_;
}

void VerletList::build_from_cells(const Box& box, const Particles& p, std::vector<std::int32_t>& upper,
                                  std::vector<std::size_t>& upper_end) const {
  std::vector<double> self(static_cast<std::size_t>(nspecies_));
  for (int s = 0; s < nspecies_; ++s) self[static_cast<std::size_t>(s)] = cutoff(s, s) + skin_;
  CellList cells;
  cells.build(box, p.x, p.y, p.z, p.species, self);
  // Each thread lists the rows of a contiguous block of particles into its own buffer; the blocks
  // are joined in order, so the list is the same for any thread count (a DPD liquid rebuilds its
  // list every few steps, and a serial build capped the two-thread speed-up).
  const std::size_t n = p.size();
  int blocks = 1;
#ifdef _OPENMP
  blocks = omp_get_max_threads();
#endif
  std::vector<std::vector<std::int32_t>> found(static_cast<std::size_t>(blocks));
#pragma omp parallel for schedule(static, 1) num_threads(blocks)
  for (int k = 0; k < blocks; ++k) {
    std::vector<std::int32_t>& mine = found[static_cast<std::size_t>(k)];
    const std::size_t begin = n * static_cast<std::size_t>(k) / static_cast<std::size_t>(blocks);
    const std::size_t end = n * (static_cast<std::size_t>(k) + 1) / static_cast<std::size_t>(blocks);
    for (std::size_t i = begin; i < end; ++i) {
      const std::size_t first = mine.size();
      const int a = p.species[i];
      for (int b = 0; b < nspecies_; ++b)
        cells.visit(b, p.position(i), cutoff(a, b) + skin_, [&](std::int32_t j, const Vec3&, double) {
          if (static_cast<std::size_t>(j) > i) mine.push_back(j);
          return false;
        });
      std::sort(mine.begin() + static_cast<std::ptrdiff_t>(first), mine.end());
      upper_end[i] = mine.size();  // within the block, for now
    }
  }
  for (int k = 0; k < blocks; ++k) {
    const std::size_t offset = upper.size();
    const std::size_t begin = n * static_cast<std::size_t>(k) / static_cast<std::size_t>(blocks);
    const std::size_t end = n * (static_cast<std::size_t>(k) + 1) / static_cast<std::size_t>(blocks);
    for (std::size_t i = begin; i < end; ++i) upper_end[i] += offset;
    upper.insert(upper.end(), found[static_cast<std::size_t>(k)].begin(), found[static_cast<std::size_t>(k)].end());
  }
}

void VerletList::build_from_candidates(const Box& box, const Particles& p, std::vector<std::int32_t>& upper,
                                       std::vector<std::size_t>& upper_end) {
  const std::size_t n = p.size();
  axis_at_.resize(n);
  for (std::size_t i = 0; i < n; ++i) axis_at_[i] = half_length(p.species[i]) > 0.0 ? Vec3(p.orientation(i) * Vec3::UnitZ()) : Vec3::Zero();
  candidates_->update(box, p);
  std::vector<double> reach2(cutoffs_.size());
  for (std::size_t k = 0; k < reach2.size(); ++k) {
    const double reach = (cutoffs_[k] + skin_) * (1.0 + kRoundOff);
    reach2[k] = reach * reach;
  }
  // Each thread prunes the rows of a contiguous block of particles, about the same number of
  // candidate pairs per block, into its own buffer; the blocks are joined in order, so the list is
  // the same for any thread count.
  int blocks = 1;
#ifdef _OPENMP
  blocks = omp_get_max_threads();
#endif
  const std::vector<std::size_t>& candidate_start = candidates_->first_pair_;  // of each row; [n]: the total
  std::vector<std::size_t> block_start(static_cast<std::size_t>(blocks) + 1, n);
  for (int k = 0; k < blocks; ++k) {
    const std::size_t share = candidate_start[n] / static_cast<std::size_t>(blocks) * static_cast<std::size_t>(k);
    block_start[static_cast<std::size_t>(k)] =
        static_cast<std::size_t>(std::lower_bound(candidate_start.begin(), candidate_start.end() - 1, share) - candidate_start.begin());
  }
  std::vector<std::vector<std::int32_t>> found(static_cast<std::size_t>(blocks));
#pragma omp parallel for schedule(static, 1) num_threads(blocks)
  for (int k = 0; k < blocks; ++k) {
    std::vector<std::int32_t>& mine = found[static_cast<std::size_t>(k)];
    for (std::size_t i = block_start[static_cast<std::size_t>(k)]; i < block_start[static_cast<std::size_t>(k) + 1]; ++i) {
      const int a = p.species[i];
      const double ha = half_length(a);
      const Vec3 ri = p.position(i);
      const Vec3& ui = axis_at_[i];
      for (const std::int32_t j : candidates_->partners_above(i)) {
        const auto uj_index = static_cast<std::size_t>(j);
        const int b = p.species[uj_index];
        const double hb = half_length(b), r2 = reach2[static_cast<std::size_t>(a * nspecies_ + b)];
        const Vec3 d = box.min_image(p.position(uj_index) - ri);
        if (ha > 0.0 && hb > 0.0) {
          // The distance of the infinite axes is a lower bound of the segments' distance and rejects
          // most candidates of long rods before the exact test.
          const Vec3 normal = ui.cross(axis_at_[uj_index]);
          const double n2 = normal.squaredNorm(), dn = d.dot(normal);
          if (dn * dn >= r2 * n2 && r2 * n2 > kAxesAccurate * d.squaredNorm()) continue;
        }
        if (segment_segment_dist2(ui, ha, axis_at_[uj_index], hb, d) < r2) mine.push_back(j);
      }
      upper_end[i] = mine.size();  // within the block, for now
    }
  }
  for (int k = 0; k < blocks; ++k) {
    const std::size_t offset = upper.size();
    for (std::size_t i = block_start[static_cast<std::size_t>(k)]; i < block_start[static_cast<std::size_t>(k) + 1]; ++i) upper_end[i] += offset;
    upper.insert(upper.end(), found[static_cast<std::size_t>(k)].begin(), found[static_cast<std::size_t>(k)].end());
  }
}

}  // namespace anisodyn

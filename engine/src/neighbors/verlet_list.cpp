#include "anisodyn/neighbors/verlet_list.hpp"

#include <algorithm>
#include <utility>

#include "anisodyn/neighbors/cell_list.hpp"

namespace anisodyn {

VerletList::VerletList(std::vector<double> cutoffs, int nspecies, double skin)
    : cutoffs_(std::move(cutoffs)), nspecies_(nspecies), skin_(skin) {}

bool VerletList::update(const Box& box, const Particles& p) {
  bool stale = built_at_.size() != p.size() || box.edges() != box_.edges();
  const double limit2 = 0.25 * skin_ * skin_;
  for (std::size_t i = 0; !stale && i < p.size(); ++i)
    stale = box.min_image(p.position(i) - built_at_[i]).squaredNorm() > limit2;
  if (stale) build(box, p);
  return stale;
}

void VerletList::build(const Box& box, const Particles& p) {
  box_ = box;
  built_at_.resize(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) built_at_[i] = p.position(i);
  std::vector<double> self(static_cast<std::size_t>(nspecies_));
  for (int s = 0; s < nspecies_; ++s) self[static_cast<std::size_t>(s)] = cutoff(s, s) + skin_;
  CellList cells;
  cells.build(box, p.x, p.y, p.z, p.species, self);
  offsets_.assign(p.size() + 1, 0);
  partners_.clear();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const std::size_t first = partners_.size();
    const int a = p.species[i];
    for (int b = 0; b < nspecies_; ++b)
      cells.visit(b, p.position(i), cutoff(a, b) + skin_, [&](std::int32_t j, const Vec3&, double) {
        if (static_cast<std::size_t>(j) != i) partners_.push_back(j);
        return false;
      });
    std::sort(partners_.begin() + static_cast<std::ptrdiff_t>(first), partners_.end());
    offsets_[i + 1] = partners_.size();
  }
  ++builds_;
}

}  // namespace anisodyn

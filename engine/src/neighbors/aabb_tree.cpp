#include "anisodyn/neighbors/aabb_tree.hpp"

#include <array>
#include <bit>
#include <numeric>
#include <utility>
#include <string>

namespace anisodyn {

namespace {
// Insertions after a build before the tree is rebuilt from scratch: on doubling, so that a state
// grown one particle at a time (lattice insertion walks the box in order and would otherwise
// deepen one branch) keeps a balanced tree at an amortised O(log N) per insertion.
constexpr std::size_t kMinRebuildSize = 16;

double volume(const Vec3& lo, const Vec3& hi) { return (hi - lo).cwiseMax(0.0).prod(); }
}  // namespace

void AabbTree::clear() {
  size_ = size_at_build_ = 0;
  nodes_.clear();
  for (auto* v : {&cx_, &cy_, &cz_, &hx_, &hy_, &hz_}) v->clear();
  id_.clear();
  count_.clear();
  leaf_node_.clear();
  leaf_of_.clear();
  slot_of_.clear();
}

void AabbTree::build(const Box& box, const std::vector<std::int32_t>& particles, const std::vector<Vec3>& centres,
                     const std::vector<Vec3>& half_extents) {
  // The query's images assume r_j − r ∈ (−L, L), i.e. wrapped centres: check once per build.
  const Vec3& L = box.edges();
  for (const std::int32_t p : particles) {
    if (p < 0 || static_cast<std::size_t>(p) >= centres.size() || static_cast<std::size_t>(p) >= half_extents.size())
      throw std::invalid_argument("AabbTree::build: particle index " + std::to_string(p) +
                                  " outside the centre or half-extent arrays");
    const Vec3& c = centres[static_cast<std::size_t>(p)];
    if (!((c.array() >= 0.0).all() && (c.array() < L.array()).all()))
      throw std::invalid_argument("AabbTree::build: centre of particle " + std::to_string(p) +
                                  " is not wrapped into [0, L)");
  }
  build_unchecked(particles, centres, half_extents);
}

void AabbTree::build_unchecked(std::vector<std::int32_t> particles, const std::vector<Vec3>& centres,
                               const std::vector<Vec3>& half_extents) {
  clear();
  if (particles.empty()) return;
  const std::int32_t max_id = *std::max_element(particles.begin(), particles.end());
  leaf_of_.assign(static_cast<std::size_t>(max_id) + 1, -1);
  slot_of_.assign(static_cast<std::size_t>(max_id) + 1, -1);
  std::vector<BuildEntry> entries;
  entries.reserve(particles.size());
  for (const std::int32_t p : particles)
    entries.push_back({centres[static_cast<std::size_t>(p)], half_extents[static_cast<std::size_t>(p)], p});
  nodes_.reserve(particles.size() / 2 + 1);
  nodes_.emplace_back();
  build_node(entries.data(), entries.data() + entries.size(), 0);
  size_ = size_at_build_ = particles.size();
}

void AabbTree::build_node(BuildEntry* first, BuildEntry* last, std::int32_t node) {
  const auto n = last - first;
  if (n <= kLeafCapacity) {
    const std::int32_t leaf = new_leaf(node);
    for (int s = 0; s < n; ++s) put(leaf, s, first[s].id, first[s].centre, first[s].half);
    count_[static_cast<std::size_t>(leaf)] = static_cast<std::int32_t>(n);
    refit(node);
    return;
  }
  // Median split of the centres (balanced by count, so the depth is log2(N / leaf size) whatever
  // the density), along the axis where the centres spread over the largest fraction of the node's
  // box: the children's boxes overlap by the entries' extents along the split axis, so splitting a
  // node of nematic rods across their length would barely shrink them.
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  Vec3 box_lo = lo, box_hi = hi;
  for (auto* e = first; e != last; ++e) {
    lo = lo.cwiseMin(e->centre);
    hi = hi.cwiseMax(e->centre);
    box_lo = box_lo.cwiseMin(e->centre - e->half);
    box_hi = box_hi.cwiseMax(e->centre + e->half);
  }
  int axis = 0;
  (hi - lo).cwiseQuotient((box_hi - box_lo).cwiseMax(1e-300)).maxCoeff(&axis);
  BuildEntry* mid = first + n / 2;
  std::nth_element(first, mid, last, [axis](const BuildEntry& a, const BuildEntry& b) { return a.centre[axis] < b.centre[axis]; });
  const auto child = static_cast<std::int32_t>(nodes_.size());
  nodes_.emplace_back();
  nodes_.emplace_back();
  nodes_[static_cast<std::size_t>(node)].child = child;
  nodes_[static_cast<std::size_t>(child)].parent = nodes_[static_cast<std::size_t>(child) + 1].parent = node;
  build_node(first, mid, child);
  build_node(mid, last, child + 1);
  refit(node);
}

std::int32_t AabbTree::new_leaf(std::int32_t node) {
  const auto leaf = static_cast<std::int32_t>(count_.size());
  count_.push_back(0);
  leaf_node_.push_back(node);
  const std::size_t slots = count_.size() * kLeafCapacity;
  for (auto* v : {&cx_, &cy_, &cz_}) v->resize(slots, std::numeric_limits<double>::quiet_NaN());
  for (auto* v : {&hx_, &hy_, &hz_}) v->resize(slots, 0.0);
  id_.resize(slots, -1);
  nodes_[static_cast<std::size_t>(node)].leaf = leaf;
  nodes_[static_cast<std::size_t>(node)].child = -1;
  return leaf;
}

void AabbTree::put(std::int32_t leaf, int slot, std::int32_t particle, const Vec3& r, const Vec3& h) {
  const std::size_t i = static_cast<std::size_t>(leaf) * kLeafCapacity + static_cast<std::size_t>(slot);
  cx_[i] = r.x(); cy_[i] = r.y(); cz_[i] = r.z();
  hx_[i] = h.x(); hy_[i] = h.y(); hz_[i] = h.z();
  id_[i] = particle;
  if (static_cast<std::size_t>(particle) >= leaf_of_.size()) {
    leaf_of_.resize(static_cast<std::size_t>(particle) + 1, -1);
    slot_of_.resize(static_cast<std::size_t>(particle) + 1, -1);
  }
  leaf_of_[static_cast<std::size_t>(particle)] = leaf;
  slot_of_[static_cast<std::size_t>(particle)] = slot;
}

void AabbTree::clear_slot(std::int32_t leaf, int slot) {
  const std::size_t i = static_cast<std::size_t>(leaf) * kLeafCapacity + static_cast<std::size_t>(slot);
  cx_[i] = cy_[i] = cz_[i] = std::numeric_limits<double>::quiet_NaN();
  hx_[i] = hy_[i] = hz_[i] = 0.0;
  id_[i] = -1;
}

bool AabbTree::refit(std::int32_t node) {
  Node& n = nodes_[static_cast<std::size_t>(node)];
  double lo[3], hi[3];
  if (n.leaf >= 0) {
    const std::size_t base = static_cast<std::size_t>(n.leaf) * kLeafCapacity;
    const double* c[3] = {cx_.data() + base, cy_.data() + base, cz_.data() + base};
    const double* h[3] = {hx_.data() + base, hy_.data() + base, hz_.data() + base};
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::numeric_limits<double>::infinity();
      hi[k] = -lo[k];
      for (int s = 0; s < count_[static_cast<std::size_t>(n.leaf)]; ++s) {
        lo[k] = std::min(lo[k], c[k][s] - h[k][s]);
        hi[k] = std::max(hi[k], c[k][s] + h[k][s]);
      }
    }
  } else {
    const Node& a = nodes_[static_cast<std::size_t>(n.child)];
    const Node& b = nodes_[static_cast<std::size_t>(n.child) + 1];
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(a.lo[k], b.lo[k]);
      hi[k] = std::max(a.hi[k], b.hi[k]);
    }
  }
  bool changed = false;
  for (int k = 0; k < 3; ++k) {
    changed |= lo[k] != n.lo[k] || hi[k] != n.hi[k];
    n.lo[k] = lo[k];
    n.hi[k] = hi[k];
  }
  return changed;
}

void AabbTree::refit_up(std::int32_t node) {
  // Boxes are exact unions of their children's, so the walk stops where a box is unchanged.
  while (node >= 0 && refit(node)) node = nodes_[static_cast<std::size_t>(node)].parent;
}

void AabbTree::move(std::int32_t particle, const Vec3& r, const Vec3& half_extent) {
  if (!contains(particle))
    throw std::invalid_argument("AabbTree::move: particle " + std::to_string(particle) + " is not in the tree");
  const std::int32_t leaf = leaf_of_[static_cast<std::size_t>(particle)];
  put(leaf, slot_of_[static_cast<std::size_t>(particle)], particle, r, half_extent);
  refit_up(leaf_node_[static_cast<std::size_t>(leaf)]);
}

void AabbTree::insert(std::int32_t particle, const Vec3& r, const Vec3& half_extent) {
  if (particle < 0 || contains(particle))
    throw std::invalid_argument("AabbTree::insert: particle " + std::to_string(particle) +
                                " is negative or already in the tree");
  if (nodes_.empty()) {
    nodes_.emplace_back();
    const std::int32_t leaf = new_leaf(0);
    put(leaf, 0, particle, r, half_extent);
    count_[0] = 1;
    refit(0);
    size_ = 1;
    return;
  }
  if (size_ + 1 >= 2 * std::max(size_at_build_, kMinRebuildSize)) return rebuild_with(particle, r, half_extent);
  const std::int32_t node = choose_leaf(r, half_extent);
  const std::int32_t leaf = nodes_[static_cast<std::size_t>(node)].leaf;
  std::int32_t& count = count_[static_cast<std::size_t>(leaf)];
  if (count < kLeafCapacity) {
    put(leaf, count++, particle, r, half_extent);
    ++size_;
    refit_up(node);
    return;
  }
  if (node_depth(node) + 1 > depth_limit()) return rebuild_with(particle, r, half_extent);
  split_leaf(node, particle, r, half_extent);
  ++size_;
}

void AabbTree::refit_all(const std::vector<Vec3>& centres, const std::vector<Vec3>& half_extents) {
  for (std::size_t leaf = 0; leaf < count_.size(); ++leaf)
    for (int s = 0; s < count_[leaf]; ++s) {
      const std::size_t i = leaf * kLeafCapacity + static_cast<std::size_t>(s);
      const auto p = static_cast<std::size_t>(id_[i]);
      if (p >= centres.size() || p >= half_extents.size())
        throw std::invalid_argument("AabbTree::refit_all: particle " + std::to_string(p) +
                                    " outside the centre or half-extent arrays");
      cx_[i] = centres[p].x(); cy_[i] = centres[p].y(); cz_[i] = centres[p].z();
      hx_[i] = half_extents[p].x(); hy_[i] = half_extents[p].y(); hz_[i] = half_extents[p].z();
    }
  // Children always come after their parent in the array (builds and leaf splits append them),
  // so one backward pass sees every child before its parent.
  for (auto node = static_cast<std::int32_t>(nodes_.size()) - 1; node >= 0; --node) refit(node);
}

std::int32_t AabbTree::choose_leaf(const Vec3& r, const Vec3& h) const {
  // Descend into the child whose box grows least to take the new one; when both already hold it
  // (or grow alike), into the one whose centre is nearer.
  const Vec3 lo = r - h, hi = r + h;
  auto cost = [&](const Node& m) {
    const Vec3 mlo(m.lo[0], m.lo[1], m.lo[2]), mhi(m.hi[0], m.hi[1], m.hi[2]);
    const double grow = volume(mlo.cwiseMin(lo), mhi.cwiseMax(hi)) - volume(mlo, mhi);
    return std::make_pair(grow, (0.5 * (mlo + mhi) - r).squaredNorm());
  };
  std::int32_t node = 0;
  while (nodes_[static_cast<std::size_t>(node)].leaf < 0) {
    const std::int32_t c = nodes_[static_cast<std::size_t>(node)].child;
    node = cost(nodes_[static_cast<std::size_t>(c)]) <= cost(nodes_[static_cast<std::size_t>(c) + 1]) ? c : c + 1;
  }
  return node;
}

void AabbTree::split_leaf(std::int32_t node, std::int32_t particle, const Vec3& r, const Vec3& h) {
  // The full leaf's entries plus the new one, split at the median along their longest axis; the
  // old leaf's slots take the lower half, a new leaf the upper.
  constexpr int m = kLeafCapacity + 1;
  const std::int32_t leaf = nodes_[static_cast<std::size_t>(node)].leaf;
  const std::size_t base = static_cast<std::size_t>(leaf) * kLeafCapacity;
  std::array<std::int32_t, m> ids;
  std::array<Vec3, m> c, e;
  for (int s = 0; s < kLeafCapacity; ++s) {
    const std::size_t i = base + static_cast<std::size_t>(s);
    ids[s] = id_[i];
    c[s] = Vec3(cx_[i], cy_[i], cz_[i]);
    e[s] = Vec3(hx_[i], hy_[i], hz_[i]);
  }
  ids[kLeafCapacity] = particle;
  c[kLeafCapacity] = r;
  e[kLeafCapacity] = h;
  Vec3 lo = c[0], hi = c[0];
  for (const Vec3& x : c) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  std::array<int, m> order;
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return c[a][axis] < c[b][axis]; });

  const auto child = static_cast<std::int32_t>(nodes_.size());
  nodes_.emplace_back();
  nodes_.emplace_back();
  nodes_[static_cast<std::size_t>(child)].parent = nodes_[static_cast<std::size_t>(child) + 1].parent = node;
  nodes_[static_cast<std::size_t>(child)].leaf = leaf;
  leaf_node_[static_cast<std::size_t>(leaf)] = child;
  const std::int32_t upper = new_leaf(child + 1);
  nodes_[static_cast<std::size_t>(node)].leaf = -1;
  nodes_[static_cast<std::size_t>(node)].child = child;
  constexpr int half = m / 2;
  for (int s = 0; s < m; ++s) {
    const int o = order[static_cast<std::size_t>(s)];
    if (s < half)
      put(leaf, s, ids[o], c[o], e[o]);
    else
      put(upper, s - half, ids[o], c[o], e[o]);
  }
  for (int s = half; s < kLeafCapacity; ++s) clear_slot(leaf, s);
  count_[static_cast<std::size_t>(leaf)] = half;
  count_[static_cast<std::size_t>(upper)] = m - half;
  refit(child);
  refit(child + 1);
  refit_up(node);
}

void AabbTree::rebuild_with(std::int32_t particle, const Vec3& r, const Vec3& h) {
  const std::size_t n = std::max(leaf_of_.size(), static_cast<std::size_t>(particle) + 1);
  std::vector<Vec3> centres(n, Vec3::Zero()), halves(n, Vec3::Zero());
  std::vector<std::int32_t> particles;
  particles.reserve(size_ + 1);
  for (std::size_t leaf = 0; leaf < count_.size(); ++leaf)
    for (int s = 0; s < count_[leaf]; ++s) {
      const std::size_t i = leaf * kLeafCapacity + static_cast<std::size_t>(s);
      particles.push_back(id_[i]);
      centres[static_cast<std::size_t>(id_[i])] = Vec3(cx_[i], cy_[i], cz_[i]);
      halves[static_cast<std::size_t>(id_[i])] = Vec3(hx_[i], hy_[i], hz_[i]);
    }
  particles.push_back(particle);
  centres[static_cast<std::size_t>(particle)] = r;
  halves[static_cast<std::size_t>(particle)] = h;
  build_unchecked(std::move(particles), centres, halves);
}

int AabbTree::node_depth(std::int32_t node) const {
  int d = 0;
  for (; node >= 0; node = nodes_[static_cast<std::size_t>(node)].parent) ++d;
  return d;
}

int AabbTree::depth_limit() const {
  // Twice a balanced tree's depth (at least 16): insertions in sorted order, which deepen one
  // branch by a level every few particles, then rebuild every O(log N) insertions; capped so the
  // traversal stack cannot overflow.
  const int balanced = static_cast<int>(std::bit_width(size_ / 4 + 1)) + 1;
  return std::min(kStackSize - 2, std::max(16, 2 * balanced));
}

int AabbTree::depth() const {
  int d = 0;
  for (const std::int32_t node : leaf_node_) d = std::max(d, node_depth(node));
  return d;
}

std::size_t AabbTree::entries_tested(const Box& box, const Vec3& r, const Vec3& half_extent) const {
  std::size_t n = 0;
  search(box, r, half_extent, [&](std::int32_t leaf, const Image&) {
    n += static_cast<std::size_t>(count_[static_cast<std::size_t>(leaf)]);
    return false;
  });
  return n;
}

}  // namespace anisodyn

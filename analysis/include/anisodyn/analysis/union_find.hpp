#pragma once
// Disjoint sets (union by size, path halving) and the connected components of a graph given as a
// list of bonds: the cluster definition of spec 50 §5.1–5.2 (Sevick, Monson & Ottino 1988).
#include <cstddef>
#include <numeric>
#include <utility>
#include <vector>

namespace anisodyn::analysis {

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n), size_(n, 1) { std::iota(parent_.begin(), parent_.end(), std::size_t{0}); }

  std::size_t find(std::size_t i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];  // path halving keeps the trees flat without recursion
      i = parent_[i];
    }
    return i;
  }
  /// Joins the sets of a and b; returns false when they were already one set.
  bool unite(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
    return true;
  }
  std::size_t size() const { return parent_.size(); }

 private:
  std::vector<std::size_t> parent_, size_;
};

using Bond = std::pair<std::size_t, std::size_t>;

/// Connected components: label[i] ∈ [0, count), numbered in order of each component's lowest
/// member, and size[c] = members of component c.
struct Components {
  std::vector<std::size_t> label;
  std::vector<std::size_t> size;
  std::size_t count() const { return size.size(); }
  /// Members of each component, ascending.
  std::vector<std::vector<std::size_t>> members() const {
    std::vector<std::vector<std::size_t>> m(size.size());
    for (std::size_t i = 0; i < label.size(); ++i) m[label[i]].push_back(i);
    return m;
  }
  /// The size of the component of every element (the cluster size l of each particle).
  std::vector<std::size_t> size_of_each() const {
    std::vector<std::size_t> s(label.size());
    for (std::size_t i = 0; i < label.size(); ++i) s[i] = size[label[i]];
    return s;
  }
};

/// Components of n elements joined by `bonds` (isolated elements are components of size 1).
inline Components connected_components(std::size_t n, const std::vector<Bond>& bonds) {
  UnionFind uf(n);
  for (const auto& [a, b] : bonds) uf.unite(a, b);
  Components c;
  c.label.assign(n, 0);
  std::vector<std::size_t> root_label(n, n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t r = uf.find(i);
    if (root_label[r] == n) {
      root_label[r] = c.size.size();
      c.size.push_back(0);
    }
    c.label[i] = root_label[r];
    ++c.size[c.label[i]];
  }
  return c;
}

}  // namespace anisodyn::analysis

#pragma once
// A bounding-volume hierarchy of axis-aligned boxes (AABB tree) over the particles of one species,
// for the hard-particle overlap search.
//
// Why: the per-species cell grid (cell_list.hpp) needs cells at least as wide as the pair cut-off,
// twice the circumradius. For long particles in boxes only a few lengths wide (boards 12×1×1 at
// η = 0.34: a box of 41 T, three cells) the grid falls back to scanning every particle, although a
// rod's neighbours fill a thin slab around it. Here each particle is bounded by its lab-frame box
// [r − h, r + h] (h from Shape::lab_half_extents), and a query descends only into nodes whose box
// overlaps the query's, so a nematic rod meets a handful of candidates whatever the box.
//
// Layout: nodes in one contiguous array, children of a node side by side; leaves hold up to
// kLeafCapacity entries as structure-of-arrays (centre and half-extent per slot), so a leaf test
// reads contiguous memory. Positions are wrapped into [0, L); node boxes may reach outside it.
// An accepted move refits the boxes on the path to the root (O(depth)); the tree's quality decays
// as particles wander, and the caller rebuilds it (once per sweep).
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <stdexcept>
#include <vector>

#include "anisodyn/core/box.hpp"
#include "anisodyn/core/types.hpp"

namespace anisodyn {

class AabbTree {
 public:
  static constexpr int kLeafCapacity = 8;

  /// Builds the tree over `particles` (global indices); centres[p] (wrapped into [0, L)) and
  /// half_extents[p] are indexed by the global index p, as in SpeciesGrid.
  void build(const Box& box, const std::vector<std::int32_t>& particles, const std::vector<Vec3>& centres,
             const std::vector<Vec3>& half_extents);
  void clear();
  /// Updates a particle already in the tree (call after an accepted move); r wrapped into [0, L).
  void move(std::int32_t particle, const Vec3& r, const Vec3& half_extent);
  /// Re-reads the centre (wrapped into [0, L)) and half-extent of every particle in the tree,
  /// indexed as in build(), and refits every box, keeping the tree's shape: O(N), against the
  /// build's O(N log N), after all particles have moved a little (a domain sweep, a rescaled box).
  /// The shape was chosen for the old positions, so the caller rebuilds once they have moved far.
  void refit_all(const std::vector<Vec3>& centres, const std::vector<Vec3>& half_extents);
  /// Adds a particle not yet in the tree; r wrapped into [0, L).
  void insert(std::int32_t particle, const Vec3& r, const Vec3& half_extent);

  /// Calls f(j, d, r2) for every particle j whose box overlaps the query box [r − h, r + h]
  /// (|d_k| ≤ h_k + h_j,k on every axis) and whose centre lies within rc (|d|² ≤ rc², pass infinity
  /// to disable), where d = r_j − r is the minimum-image separation. Each j is visited at most once;
  /// stops and returns true as soon as f does. r must be wrapped into the box. Thread-safe (const,
  /// no scratch state). Overlaps under a non-minimum image are not reported, so the box must be at
  /// least twice the reach along every axis, as for the grid.
  template <class F>
  bool visit(const Box& box, const Vec3& r, const Vec3& half_extent, double rc, F&& f) const;

  /// Leaf entries a query would test (diagnostics: the work of visit() without the rc filter).
  std::size_t entries_tested(const Box& box, const Vec3& r, const Vec3& half_extent) const;

  std::size_t size() const { return size_; }
  std::size_t node_count() const { return nodes_.size(); }
  /// Levels from the root to the deepest leaf (1 for a lone leaf, 0 for an empty tree).
  int depth() const;
  bool contains(std::int32_t particle) const {
    return particle >= 0 && static_cast<std::size_t>(particle) < leaf_of_.size() && leaf_of_[particle] >= 0;
  }

 private:
  // Internal nodes have leaf < 0 and children at `child` and `child + 1`; 64 bytes, one cache line.
  struct Node {
    double lo[3], hi[3];
    std::int32_t parent = -1, child = -1, leaf = -1, pad = 0;
  };
  // The query seen under one periodic image: q = r + shift, plus the range of r_j − r for which
  // this image is the minimum one (so each j is reported under one image only).
  struct Image {
    Vec3 q, shift, e_lo, e_hi;
  };
  // The traversal stack holds at most depth + 1 nodes; insert() keeps the depth below depth_limit().
  static constexpr int kStackSize = 64;

  template <class Leaf>
  bool search(const Box& box, const Vec3& r, const Vec3& half_extent, Leaf&& leaf_fn) const;
  bool overlaps(const Node& n, const Vec3& q, const Vec3& h) const;

  /// build() without the check of the inputs (also used to rebuild on insert).
  void build_unchecked(std::vector<std::int32_t> particles, const std::vector<Vec3>& centres,
                       const std::vector<Vec3>& half_extents);
  /// A particle as the build sees it: contiguous, so that the per-node bounds and the median
  /// split read sequential memory instead of gathering through the particle index.
  struct BuildEntry {
    Vec3 centre, half;
    std::int32_t id;
  };
  void build_node(BuildEntry* first, BuildEntry* last, std::int32_t node);
  std::int32_t new_leaf(std::int32_t node);
  void put(std::int32_t leaf, int slot, std::int32_t particle, const Vec3& r, const Vec3& h);
  void clear_slot(std::int32_t leaf, int slot);
  /// Exact box of a node from its entries or children; returns whether it changed.
  bool refit(std::int32_t node);
  void refit_up(std::int32_t node);
  std::int32_t choose_leaf(const Vec3& r, const Vec3& h) const;
  void split_leaf(std::int32_t node, std::int32_t particle, const Vec3& r, const Vec3& h);
  int node_depth(std::int32_t node) const;
  int depth_limit() const;
  void rebuild_with(std::int32_t particle, const Vec3& r, const Vec3& h);

  std::size_t size_ = 0, size_at_build_ = 0;
  std::vector<Node> nodes_;
  // Leaf slots, leaf-major: slot s of leaf l at l * kLeafCapacity + s; unused slots have NaN
  // centres.
  std::vector<double> cx_, cy_, cz_, hx_, hy_, hz_;
  std::vector<std::int32_t> id_;
  std::vector<std::int32_t> count_, leaf_node_;  // per leaf
  std::vector<std::int32_t> leaf_of_, slot_of_;  // per particle (global index), −1 when absent
};

// ---- inline implementation of the query --------------------------------------------------------

inline bool AabbTree::overlaps(const Node& n, const Vec3& q, const Vec3& h) const {
  return n.lo[0] <= q.x() + h.x() && n.hi[0] >= q.x() - h.x() && n.lo[1] <= q.y() + h.y() &&
         n.hi[1] >= q.y() - h.y() && n.lo[2] <= q.z() + h.z() && n.hi[2] >= q.z() - h.z();
}

template <class Leaf>
bool AabbTree::search(const Box& box, const Vec3& r, const Vec3& half_extent, Leaf&& leaf_fn) const {
  if (nodes_.empty()) return false;
  const Vec3& L = box.edges();
  // Nodes are tested with a slightly padded query so that rounding never prunes a leaf whose
  // entry touches the query; the exact test is the leaf's.
  const Vec3 hn = half_extent + Vec3::Constant(1e-12 * L.maxCoeff());
  const Node& root = nodes_[0];
  // Per axis, the images of the query (shifts 0, −L, +L) whose box reaches the root's: usually
  // only the unshifted one, two near a face. The shifted image covers r_j − r beyond ∓L/2.
  const double inf = std::numeric_limits<double>::infinity();
  double shift[3][3], e_lo[3][3], e_hi[3][3];
  int n_shift[3];
  for (int k = 0; k < 3; ++k) {
    n_shift[k] = 0;
    for (int s : {0, -1, 1}) {
      const double q = r[k] + s * L[k];
      if (root.lo[k] > q + hn[k] || root.hi[k] < q - hn[k]) continue;
      shift[k][n_shift[k]] = s * L[k];
      e_lo[k][n_shift[k]] = s == 0 ? -0.5 * L[k] : (s > 0 ? 0.5 * L[k] : -inf);
      e_hi[k][n_shift[k]] = s == 0 ? 0.5 * L[k] : (s > 0 ? inf : -0.5 * L[k]);
      ++n_shift[k];
    }
  }
  std::int32_t stack[kStackSize];
  for (int a = 0; a < n_shift[0]; ++a)
    for (int b = 0; b < n_shift[1]; ++b)
      for (int c = 0; c < n_shift[2]; ++c) {
        Image im;
        im.shift = Vec3(shift[0][a], shift[1][b], shift[2][c]);
        im.q = r + im.shift;
        im.e_lo = Vec3(e_lo[0][a], e_lo[1][b], e_lo[2][c]);
        im.e_hi = Vec3(e_hi[0][a], e_hi[1][b], e_hi[2][c]);
        // Children are tested before they are pushed, so the stack holds only overlapping nodes
        // (the root overlaps: the images were chosen so).
        int sp = 0;
        stack[sp++] = 0;
        while (sp > 0) {
          const Node& n = nodes_[static_cast<std::size_t>(stack[--sp])];
          if (n.leaf >= 0) {
            if (leaf_fn(n.leaf, im)) return true;
            continue;
          }
          if (sp + 2 > kStackSize)
            throw std::length_error("AabbTree: traversal stack overflow (tree deeper than its stack; rebuild it)");
          const Node& c0 = nodes_[static_cast<std::size_t>(n.child)];
          const Node& c1 = nodes_[static_cast<std::size_t>(n.child) + 1];
          const bool in0 = overlaps(c0, im.q, hn), in1 = overlaps(c1, im.q, hn);
          if (in0 && in1) {
            // Nearer child on top: most trial moves are rejected, and a rejection ends at the
            // first overlap, which is usually in the nearer child.
            auto dist2 = [&](const Node& m) {
              double s = 0.0;
              for (int k = 0; k < 3; ++k) {
                const double d = 0.5 * (m.lo[k] + m.hi[k]) - im.q[k];
                s += d * d;
              }
              return s;
            };
            const bool first_is_nearer = dist2(c0) <= dist2(c1);
            stack[sp++] = first_is_nearer ? n.child + 1 : n.child;
            stack[sp++] = first_is_nearer ? n.child : n.child + 1;
          } else if (in0 || in1) {
            stack[sp++] = in0 ? n.child : n.child + 1;
          }
        }
      }
  return false;
}

template <class F>
bool AabbTree::visit(const Box& box, const Vec3& r, const Vec3& h, double rc, F&& f) const {
  const double rc2 = rc * rc;
  return search(box, r, h, [&](std::int32_t leaf, const Image& im) {
    const std::size_t base = static_cast<std::size_t>(leaf) * kLeafCapacity;
    const double *px = cx_.data() + base, *py = cy_.data() + base, *pz = cz_.data() + base;
    const double *qx = hx_.data() + base, *qy = hy_.data() + base, *qz = hz_.data() + base;
    const double rx = r.x(), ry = r.y(), rz = r.z(), sx = im.shift.x(), sy = im.shift.y(), sz = im.shift.z();
    const double lx = im.e_lo.x(), ly = im.e_lo.y(), lz = im.e_lo.z(), ux = im.e_hi.x(), uy = im.e_hi.y(), uz = im.e_hi.z();
    // Branch-free pass over all slots of the leaf (empty ones hold NaN centres, which fail every
    // comparison), so that the loop has a fixed length and vectorises; hits are handled after.
    // e = r_j − r is computed once for every image, so that their minimum-image ranges are
    // disjoint exactly.
    double r2[kLeafCapacity];
    unsigned hits = 0;
#pragma omp simd reduction(| : hits)
    for (int s = 0; s < kLeafCapacity; ++s) {
      const double ex = px[s] - rx, ey = py[s] - ry, ez = pz[s] - rz;
      const double dx = ex - sx, dy = ey - sy, dz = ez - sz;
      r2[s] = dx * dx + dy * dy + dz * dz;
      const bool hit = (ex >= lx) & (ex < ux) & (ey >= ly) & (ey < uy) & (ez >= lz) & (ez < uz) &
                       (std::abs(dx) <= h.x() + qx[s]) & (std::abs(dy) <= h.y() + qy[s]) &
                       (std::abs(dz) <= h.z() + qz[s]) & (r2[s] <= rc2);
      hits |= static_cast<unsigned>(hit) << s;
    }
    for (; hits != 0; hits &= hits - 1) {
      const int s = std::countr_zero(hits);
      const Vec3 d(px[s] - rx - sx, py[s] - ry - sy, pz[s] - rz - sz);
      if (f(id_[base + static_cast<std::size_t>(s)], d, r2[s])) return true;
    }
    return false;
  });
}

}  // namespace anisodyn

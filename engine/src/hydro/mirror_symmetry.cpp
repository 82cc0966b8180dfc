#include "anisodyn/hydro/mirror_symmetry.hpp"

#include <cmath>
#include <optional>
#include <unordered_map>

namespace anisodyn::hydro {

namespace {

/// Spatial hash for exact-position lookups: each bead sits in a cell of side `cell`; a query
/// searches the 27 cells around its own, so a tolerance well below the cell side is safe.
class PositionIndex {
 public:
  PositionIndex(const std::vector<Vec3>& points, double cell) : points_(points), cell_(cell) {
    for (std::size_t i = 0; i < points.size(); ++i) cells_[key(cell_of(points[i]))].push_back(i);
  }

  std::optional<std::size_t> find(const Vec3& p, double tolerance) const {
    const Int3 c = cell_of(p);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(key(c + Int3(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (std::size_t i : it->second)
            if ((points_[i] - p).norm() <= tolerance) return i;
        }
    return std::nullopt;
  }

 private:
  Int3 cell_of(const Vec3& p) const {
    return Int3(static_cast<int>(std::floor(p.x() / cell_)), static_cast<int>(std::floor(p.y() / cell_)),
                static_cast<int>(std::floor(p.z() / cell_)));
  }
  static long long key(const Int3& c) {
    return (static_cast<long long>(c.x() + (1 << 20)) << 42) ^ (static_cast<long long>(c.y() + (1 << 20)) << 21) ^
           static_cast<long long>(c.z() + (1 << 20));
  }
  const std::vector<Vec3>& points_;
  double cell_;
  std::unordered_map<long long, std::vector<std::size_t>> cells_;
};

double typical_spacing(const std::vector<Vec3>& beads) {
  Vec3 lo = beads.front(), hi = beads.front();
  for (const auto& b : beads) { lo = lo.cwiseMin(b); hi = hi.cwiseMax(b); }
  const double extent = std::max((hi - lo).maxCoeff(), 1e-12);
  // A cell holding a few beads on average: the surface is 2-D, so ~extent/√N.
  return extent / std::max(1.0, std::sqrt(static_cast<double>(beads.size())));
}

}  // namespace

MirrorSymmetry find_mirror_symmetry(const std::vector<Vec3>& beads, double tolerance, bool use_symmetry) {
  MirrorSymmetry sym;
  const std::size_t n = beads.size();
  std::vector<std::size_t> identity(n);
  for (std::size_t i = 0; i < n; ++i) identity[i] = i;
  sym.operations.push_back({Vec3(1, 1, 1), identity});

  if (use_symmetry && n > 1) {
    const PositionIndex index(beads, typical_spacing(beads));
    for (int mask = 1; mask < 8; ++mask) {
      const Vec3 sign((mask & 1) ? -1 : 1, (mask & 2) ? -1 : 1, (mask & 4) ? -1 : 1);
      MirrorOperation op{sign, std::vector<std::size_t>(n)};
      bool invariant = true;
      for (std::size_t i = 0; i < n && invariant; ++i) {
        const auto j = index.find(beads[i].cwiseProduct(sign), tolerance);
        if (j) op.image[i] = *j; else invariant = false;
      }
      if (invariant) sym.operations.push_back(std::move(op));
    }
  }

  std::vector<bool> assigned(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    if (assigned[i]) continue;
    BeadOrbit orbit{i, {}};
    for (std::size_t g = 0; g < sym.operations.size(); ++g) {
      const std::size_t j = sym.operations[g].image[i];
      assigned[j] = true;
      if (j == i) orbit.stabilizer.push_back(static_cast<int>(g));
    }
    sym.orbits.push_back(std::move(orbit));
  }
  return sym;
}

}  // namespace anisodyn::hydro

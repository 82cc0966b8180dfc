#include "anisodyn/interactions/hard_overlap.hpp"

#include <algorithm>
#include <string>

#include "anisodyn/core/error.hpp"
#include "anisodyn/geometry/overlap.hpp"

namespace anisodyn {

void require_minimum_image(const State& state, const std::string& file) {
  const double reach = largest_pair_cutoff(state.species);
  if (state.box.shortest_edge() < 2.0 * reach)
    throw InputError(file, "/particles/all/box", "box edges of at least " + std::to_string(2.0 * reach) +
                                                     " (twice the largest cut-off) for the minimum image; shortest is " +
                                                     std::to_string(state.box.shortest_edge()));
}

double largest_pair_cutoff(const SpeciesTable& species) {
  double r = 0.0;
  for (const auto& s : species) r = std::max(r, s.shape.circumradius());
  return 2.0 * r;
}

HardOverlap::HardOverlap(const State& state, const std::vector<std::size_t>& expected_counts)
    : state_(&state), expected_counts_(expected_counts) {
  const auto& species = state.species;
  nspecies_ = static_cast<int>(species.size());
  cutoff_.assign(species.size() * species.size(), 0.0);
  for (int a = 0; a < nspecies_; ++a)
    for (int b = 0; b < nspecies_; ++b) {
      const Shape& sa = species[static_cast<std::size_t>(a)].shape;
      const Shape& sb = species[static_cast<std::size_t>(b)].shape;
      if (!overlap_supported(sa.kind, sb.kind))
        throw InputError("", "species", std::string("no overlap test for the pair ") + shape_kind_name(sa.kind) +
                                            "–" + shape_kind_name(sb.kind));
      cutoff_[static_cast<std::size_t>(a * nspecies_ + b)] = sa.circumradius() + sb.circumradius();
    }
  largest_cutoff_ = largest_pair_cutoff(species);
  rebuild(state);
}


void HardOverlap::rebuild(const State& state) {
  state_ = &state;
  const Particles& p = state.particles;
  rot_.resize(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) rot_[i] = p.orientation(i).toRotationMatrix();
  std::vector<double> self(static_cast<std::size_t>(nspecies_));
  for (int s = 0; s < nspecies_; ++s) self[static_cast<std::size_t>(s)] = cutoff(s, s);
  cells_.build(state.box, p.x, p.y, p.z, p.species, self, expected_counts_);
}

void HardOverlap::inserted(std::int32_t i) {
  const Particles& p = state_->particles;
  const std::size_t ui = static_cast<std::size_t>(i);
  rot_.resize(p.size());
  rot_[ui] = p.orientation(ui).toRotationMatrix();
  cells_.insert(i, p.species[ui], p.position(ui));
}

template <class F>
bool HardOverlap::for_each_overlap(std::int32_t i, const Vec3& r, const Mat3& rot, std::int32_t first_j, F&& on_overlap) const {
  const auto& species = state_->species;
  const int a = state_->particles.species[static_cast<std::size_t>(i)];
  const Shape& sa = species[static_cast<std::size_t>(a)].shape;
  for (int b = 0; b < nspecies_; ++b) {
    const Shape& sb = species[static_cast<std::size_t>(b)].shape;
    const double rc = cutoff(a, b);
    // The common pairs get their kernel inlined into the candidate loop; every other registered
    // pair goes through the generic dispatcher.
    auto scan = [&](auto&& kernel) {
      return cells_.visit(b, r, rc, [&](std::int32_t j, const Vec3& d, double r2) {
        return j != i && j >= first_j && kernel(j, d, r2) && on_overlap(j);
      });
    };
    bool stopped;
    if (sa.kind == ShapeKind::Sphere && sb.kind == ShapeKind::Sphere) {
      // The cut-off is the contact distance and the cell list keeps r² ≤ rc²: every candidate overlaps.
      stopped = scan([](std::int32_t, const Vec3&, double) { return true; });
    } else if (sa.kind == ShapeKind::Cuboid && sb.kind == ShapeKind::Cuboid) {
      const Vec3 ha = sa.half_extents(), hb = sb.half_extents();
      // Cheap exclusion before the 15-axis test: B lies inside its circumsphere, so if B's centre
      // is farther from box A than B's circumradius they cannot touch (and vice versa). Each check
      // is one OCSI distance (9 multiply-adds); the margin keeps round-off from excluding contact.
      const double ra2 = (1.0 + 1e-12) * ha.squaredNorm(), rb2 = (1.0 + 1e-12) * hb.squaredNorm();
      stopped = scan([&](std::int32_t j, const Vec3& d, double) {
        const Mat3& rj = rot_[static_cast<std::size_t>(j)];
        if (cuboid_sphere_dmin2(rot, ha, d) > rb2 || cuboid_sphere_dmin2(rj, hb, Vec3(-d)) > ra2) return false;
        return overlap_cuboid_cuboid(ha, rot, hb, rj, d);
      });
    } else if (sa.kind == ShapeKind::Cuboid && sb.kind == ShapeKind::Sphere) {
      const Vec3 ha = sa.half_extents();
      const double rb = 0.5 * sb.diameter;
      stopped = scan([&](std::int32_t, const Vec3& d, double) { return overlap_cuboid_sphere(rot, ha, d, rb); });
    } else if (sa.kind == ShapeKind::Sphere && sb.kind == ShapeKind::Cuboid) {
      const Vec3 hb = sb.half_extents();
      const double ra = 0.5 * sa.diameter;
      stopped = scan([&](std::int32_t j, const Vec3& d, double) { return overlap_cuboid_sphere(rot_[static_cast<std::size_t>(j)], hb, Vec3(-d), ra); });
    } else {
      stopped = scan([&](std::int32_t j, const Vec3& d, double) { return overlap(sa, rot, sb, rot_[static_cast<std::size_t>(j)], d); });
    }
    if (stopped) return true;
  }
  return false;
}

bool HardOverlap::overlaps(std::int32_t i, const Vec3& r, const Mat3& rot) const {
  return for_each_overlap(i, r, rot, 0, [](std::int32_t) { return true; });
}

int HardOverlap::count_overlaps(std::int32_t i, const Vec3& r, const Mat3& rot) const {
  int count = 0;
  for_each_overlap(i, r, rot, 0, [&](std::int32_t) { ++count; return false; });
  return count;
}

void HardOverlap::moved(std::int32_t i, const Vec3& r, const Mat3& rot) {
  rot_[static_cast<std::size_t>(i)] = rot;
  cells_.move(i, r);
}

std::optional<std::pair<std::int32_t, std::int32_t>> HardOverlap::first_overlap() const {
  const Particles& p = state_->particles;
  for (std::size_t ui = 0; ui < p.size(); ++ui) {
    const std::int32_t i = static_cast<std::int32_t>(ui);
    std::int32_t partner = -1;
    // Each pair once: only partners with a larger index.
    for_each_overlap(i, p.position(ui), rot_[ui], i + 1, [&](std::int32_t j) { partner = j; return true; });
    if (partner >= 0) return std::make_pair(i, partner);
  }
  return std::nullopt;
}

}  // namespace anisodyn

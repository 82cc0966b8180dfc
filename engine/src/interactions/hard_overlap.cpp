#include "anisodyn/interactions/hard_overlap.hpp"

#include <algorithm>
#include <string>

#include "anisodyn/core/error.hpp"
#include "anisodyn/geometry/overlap.hpp"

namespace anisodyn {

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
  rebuild(state);
}

double HardOverlap::max_cutoff() const { return cutoff_.empty() ? 0.0 : *std::max_element(cutoff_.begin(), cutoff_.end()); }

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

bool HardOverlap::overlaps(std::int32_t i, const Vec3& r, const Mat3& rot) const {
  const auto& species = state_->species;
  const int a = state_->particles.species[static_cast<std::size_t>(i)];
  const Shape& sa = species[static_cast<std::size_t>(a)].shape;
  for (int b = 0; b < nspecies_; ++b) {
    const Shape& sb = species[static_cast<std::size_t>(b)].shape;
    const double rc = cutoff(a, b);
    // The common pairs get their kernel inlined into the candidate loop; every other registered
    // pair goes through the generic dispatcher.
    auto scan = [&](auto&& kernel) {
      return cells_.visit(b, r, rc, [&](std::int32_t j, const Vec3& d, double r2) { return j != i && kernel(j, d, r2); });
    };
    bool hit;
    if (sa.kind == ShapeKind::Sphere && sb.kind == ShapeKind::Sphere) {
      // The cut-off is the contact distance and the cell list keeps r² ≤ rc²: every candidate overlaps.
      hit = scan([](std::int32_t, const Vec3&, double) { return true; });
    } else if (sa.kind == ShapeKind::Cuboid && sb.kind == ShapeKind::Cuboid) {
      const Vec3 ha = sa.half_extents(), hb = sb.half_extents();
      // Cheap exclusion before the 15-axis test: B lies inside its circumsphere, so if B's centre
      // is farther from box A than B's circumradius they cannot touch (and vice versa). Each check
      // is one OCSI distance (9 multiply-adds); the margin keeps round-off from excluding contact.
      const double ra2 = (1.0 + 1e-12) * ha.squaredNorm(), rb2 = (1.0 + 1e-12) * hb.squaredNorm();
      hit = scan([&](std::int32_t j, const Vec3& d, double) {
        const Mat3& rj = rot_[static_cast<std::size_t>(j)];
        if (cuboid_sphere_dmin2(rot, ha, d) > rb2 || cuboid_sphere_dmin2(rj, hb, Vec3(-d)) > ra2) return false;
        return overlap_cuboid_cuboid(ha, rot, hb, rj, d);
      });
    } else if (sa.kind == ShapeKind::Cuboid && sb.kind == ShapeKind::Sphere) {
      const Vec3 ha = sa.half_extents();
      const double rb = 0.5 * sb.diameter;
      hit = scan([&](std::int32_t, const Vec3& d, double) { return overlap_cuboid_sphere(rot, ha, d, rb); });
    } else if (sa.kind == ShapeKind::Sphere && sb.kind == ShapeKind::Cuboid) {
      const Vec3 hb = sb.half_extents();
      const double ra = 0.5 * sa.diameter;
      hit = scan([&](std::int32_t j, const Vec3& d, double) { return overlap_cuboid_sphere(rot_[static_cast<std::size_t>(j)], hb, Vec3(-d), ra); });
    } else {
      hit = scan([&](std::int32_t j, const Vec3& d, double) { return overlap(sa, rot, sb, rot_[static_cast<std::size_t>(j)], d); });
    }
    if (hit) return true;
  }
  return false;
}

int HardOverlap::count_overlaps(std::int32_t i, const Vec3& r, const Mat3& rot) const {
  const auto& species = state_->species;
  const int a = state_->particles.species[static_cast<std::size_t>(i)];
  const Shape& sa = species[static_cast<std::size_t>(a)].shape;
  int count = 0;
  for (int b = 0; b < nspecies_; ++b) {
    const Shape& sb = species[static_cast<std::size_t>(b)].shape;
    cells_.visit(b, r, cutoff(a, b), [&](std::int32_t j, const Vec3& d, double) {
      count += j != i && overlap(sa, rot, sb, rot_[static_cast<std::size_t>(j)], d);
      return false;
    });
  }
  return count;
}

void HardOverlap::moved(std::int32_t i, const Vec3& r, const Mat3& rot) {
  rot_[static_cast<std::size_t>(i)] = rot;
  cells_.move(i, r);
}

std::optional<std::pair<std::int32_t, std::int32_t>> HardOverlap::first_overlap() const {
  const Particles& p = state_->particles;
  const auto& species = state_->species;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int a = p.species[i];
    const Shape& sa = species[static_cast<std::size_t>(a)].shape;
    std::int32_t partner = -1;
    for (int b = 0; b < nspecies_ && partner < 0; ++b) {
      const Shape& sb = species[static_cast<std::size_t>(b)].shape;
      cells_.visit(b, p.position(i), cutoff(a, b), [&](std::int32_t j, const Vec3& d, double) {
        if (j <= static_cast<std::int32_t>(i) || !overlap(sa, rot_[i], sb, rot_[static_cast<std::size_t>(j)], d)) return false;
        partner = j;
        return true;
      });
    }
    if (partner >= 0) return std::make_pair(static_cast<std::int32_t>(i), partner);
  }
  return std::nullopt;
}

}  // namespace anisodyn

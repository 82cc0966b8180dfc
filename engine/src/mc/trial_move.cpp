#include "anisodyn/mc/trial_move.hpp"

#include <cmath>

#include "anisodyn/core/quaternion.hpp"

namespace anisodyn {

void MoveCounters::reset(std::size_t nspecies) {
  translate_tried.assign(nspecies, 0);
  translate_accepted.assign(nspecies, 0);
  rotate_tried.assign(nspecies, 0);
  rotate_accepted.assign(nspecies, 0);
  volume_tried = volume_accepted = 0;
}

void MoveCounters::add_particle_moves(const MoveCounters& other, std::int64_t sign) {
  for (std::size_t s = 0; s < translate_tried.size(); ++s) {
    translate_tried[s] += sign * other.translate_tried[s];
    translate_accepted[s] += sign * other.translate_accepted[s];
    rotate_tried[s] += sign * other.rotate_tried[s];
    rotate_accepted[s] += sign * other.rotate_accepted[s];
  }
}

MoveCounters MoveCounters::since(const MoveCounters& earlier) const {
  MoveCounters d = *this;
  d.add_particle_moves(earlier, -1);
  d.volume_tried -= earlier.volume_tried;
  d.volume_accepted -= earlier.volume_accepted;
  return d;
}

void TrialMove::attempt(std::int32_t i) const {
  Particles& p = state.particles;
  const std::size_t ui = static_cast<std::size_t>(i);
  const int s = p.species[ui];
  const auto us = static_cast<std::size_t>(s);
  const Shape& shape = state.species[us].shape;
  const Mat3& rot = overlap.rotation(i);
  const bool rotate = shape.is_anisotropic() && rng.uniform() < 0.5;

  if (!rotate) {
    const double d = moves.translate[us];
    const Vec3 body(rng.uniform(-d, d), rng.uniform(-d, d), rng.uniform(-d, d));
    Vec3 r = p.position(ui) + rot * body;
    Int3 image = p.image(ui);
    state.box.wrap(r, image);
    counters.translate_tried[us]++;
    if (domain && leaves_domain(s, r, rot)) return;
    if (blocked(i, r, rot, p.position(ui), rot)) return;
    p.set_position(ui, r);
    p.set_image(ui, image);
    overlap.moved(i, r, rot);
    counters.translate_accepted[us]++;
    return;
  }

  const double a = moves.rotate[us];
  const Vec3 theta(rng.uniform(-a, a), rng.uniform(-a, a), rng.uniform(-a, a));
  const Quat q = rotate_in_body_frame(p.orientation(ui), theta);
  const Mat3 new_rot = q.toRotationMatrix();
  counters.rotate_tried[us]++;
  if (field.active()) {
    // Metropolis on the field energy first: it is cheap and rejects before the overlap search.
    const double dU = field.energy(new_rot) - field.energy(rot);
    if (dU > 0.0 && rng.uniform() >= std::exp(-dU)) return;
  }
  const Vec3 r = p.position(ui);
  if (domain && leaves_domain(s, r, new_rot)) return;
  if (blocked(i, r, new_rot, r, rot)) return;
  p.set_orientation(ui, q);
  overlap.moved(i, r, new_rot);
  counters.rotate_accepted[us]++;
}

bool TrialMove::blocked(std::int32_t i, const Vec3& r_new, const Mat3& rot_new, const Vec3& r_old, const Mat3& rot_old) const {
  if (!removing_overlaps) return overlap.overlaps(i, r_new, rot_new);
  // A clean particle stays clean; an overlapping one may only move if that lowers its count.
  // (Allowing equal counts lets it wander deeper into its partner, and removal then stalls.)
  const int before = overlap.count_overlaps(i, r_old, rot_old);
  if (before == 0) return overlap.overlaps(i, r_new, rot_new);
  return overlap.count_overlaps(i, r_new, rot_new) >= before;
}

bool TrialMove::leaves_domain(int species, const Vec3& r, const Mat3& rot) const {
  return !domain->holds(r, state.species[static_cast<std::size_t>(species)].shape.lab_half_extents(rot), state.box.edges());
}

}  // namespace anisodyn

#include "anisodyn/dmc/dmc_engine.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "anisodyn/core/error.hpp"
#include "anisodyn/core/quaternion.hpp"

namespace anisodyn {

namespace {
Vec3 step_sizes(const Vec3& D, double dt) {
  return Vec3(std::sqrt(2.0 * D.x() * dt), std::sqrt(2.0 * D.y() * dt), std::sqrt(2.0 * D.z() * dt));
}

Vec3 uniform_in_box(Rng& rng, const Vec3& half) {
  // Evaluated in a fixed order (x, y, z) so the sequence of draws never depends on the compiler.
  const double a = rng.uniform(-half.x(), half.x());
  const double b = rng.uniform(-half.y(), half.y());
  const double c = rng.uniform(-half.z(), half.z());
  return Vec3(a, b, c);
}
}  // namespace

DmcEngine::DmcEngine(State& state, const RngState& rng, const DmcMoveOptions& options)
    : state_(state), rng_(rng), options_(options), overlap_(state) {
  if (auto pair = overlap_.first_overlap())
    throw InputError("", "", "overlapping configuration: particles " +
                                 std::to_string(state.particles.id[static_cast<std::size_t>(pair->first)]) + " and " +
                                 std::to_string(state.particles.id[static_cast<std::size_t>(pair->second)]) + " overlap");
  const std::size_t ns = state.species.size(), n = state.particles.size();
  for (const auto& sp : state.species) anisotropic_.push_back(sp.shape.is_anisotropic() ? 1 : 0);
  dt_.assign(ns, 0.0);
  translate_cap_.assign(ns, Vec3::Zero());
  rotate_cap_.assign(ns, Vec3::Zero());
  cycle_counts_.assign(ns, TrialCounts{});
  body_displacement_.assign(3 * n, 0.0);
  body_rotation_.assign(3 * n, 0.0);
  rotation_vector_.assign(9 * n, 0.0);
}

void DmcEngine::set_time_steps(const std::vector<double>& dt) {
  dt_ = dt;
  for (std::size_t s = 0; s < dt.size(); ++s) {
    translate_cap_[s] = step_sizes(state_.species[s].D_trans, dt[s]);
    rotate_cap_[s] = anisotropic_[s] ? step_sizes(state_.species[s].D_rot, dt[s]) : Vec3::Zero();
  }
  size_skin_lists();
}

void DmcEngine::size_skin_lists() {
  // A half-skin of kSkinMoves largest moves: a body's list then serves many trials before it
  // leaves its skin (a random walk needs ~kSkinMoves² steps), while the grown bodies stay close
  // to the real ones so lists hold a few partners.
  constexpr double kSkinMoves = 4.0;
  const std::size_t ns = state_.species.size();
  std::vector<double> want(ns, 0.0);
  for (std::size_t s = 0; s < ns && s < dt_.size(); ++s) {
    if (!(dt_[s] > 0.0)) continue;
    const Mat3 swing = quat_from_rotation_vector(rotate_cap_[s]).toRotationMatrix();
    want[s] = kSkinMoves * motion_bound(state_.species[s].shape, translate_cap_[s], Mat3::Identity(), swing);
  }
  const std::vector<double>& have = skin_request_;
  bool keep = have.size() == ns;
  for (std::size_t s = 0; keep && s < ns; ++s)
    keep = (want[s] == 0.0) == (have[s] == 0.0) && want[s] <= 2.0 * have[s] && have[s] <= 2.0 * want[s];
  if (keep) return;
  skin_request_ = want;
  overlap_.use_skin_lists(std::move(want));
}

void DmcEngine::set_dipoles(const DipoleSettings& dipoles, const Vec3& direction) {
  dipoles_ = dipoles;
  dipole_direction_ = direction.normalized();
  if (!dipoles.active()) { ewald_.reset(); return; }
  std::vector<char> carries(state_.particles.size());
  for (std::size_t i = 0; i < carries.size(); ++i)
    carries[i] = dipoles.species_carries[static_cast<std::size_t>(state_.particles.species[i])];
  ewald_ = std::make_unique<DipolarEwald>(state_.box.edges(), dipole_direction_, dipoles.gamma, dipoles.ewald, std::move(carries));
  if (field_on_) set_field_on(true);
}

void DmcEngine::set_field_on(bool on) {
  field_on_ = on;
  if (on && ewald_) {
    ewald_->rebuild(state_.particles);
    dipolar_energy_ = ewald_->total_energy(state_.particles);
  }
}

void DmcEngine::set_tracer(const PulledTracer& tracer) { tracer_ = tracer; }

double DmcEngine::tracer_parallel_step() const {
  if (!tracer_.active()) return 0.0;
  const int s = state_.particles.species[static_cast<std::size_t>(tracer_.particle)];
  const double D = state_.species[static_cast<std::size_t>(s)].D_trans[tracer_.axis];
  const double dt = dt_[static_cast<std::size_t>(s)];
  const double drift = D * tracer_.beta_force * dt;
  return std::sqrt(2.0 * D * dt + drift * drift);
}

void DmcEngine::cycle() {
  for (auto& c : cycle_counts_) c = TrialCounts{};
  const std::size_t n = state_.particles.size();
  for (std::size_t t = 0; t < n; ++t) trial();
}

void DmcEngine::trial() {
  const auto i = static_cast<std::int32_t>(rng_.index(state_.particles.size()));
  const int s = state_.particles.species[static_cast<std::size_t>(i)];
  TrialCounts& c = cycle_counts_[static_cast<std::size_t>(s)];
  ++c.tried;
  if (i == tracer_.particle) tracer_move(i, s, c);
  else if (anisotropic_[static_cast<std::size_t>(s)]) roto_translation(i, s, c);
  else translation(i, s, c);
}

void DmcEngine::roto_translation(std::int32_t i, int s, TrialCounts& c) {
  const auto ui = static_cast<std::size_t>(i);
  const auto us = static_cast<std::size_t>(s);
  Particles& p = state_.particles;
  const Vec3 theta = uniform_in_box(rng_, rotate_cap_[us]);
  const Vec3 X = uniform_in_box(rng_, translate_cap_[us]);

  Quat dq;  // rotation in the body frame
  if (options_.rotation == RotationComposition::ExponentialMap) {
    dq = quat_from_rotation_vector(theta);
  } else {
    dq = Quat::Identity();
    for (int axis : options_.sequential_order) dq = dq * quat_from_rotation_vector(theta[axis] * Vec3::Unit(axis));
  }
  const Quat q_old = p.orientation(ui);
  const Quat q_new = (q_old * dq).normalized();
  const Mat3& rot_old = overlap_.rotation(i);
  const Mat3 rot_new = q_new.toRotationMatrix();
  Vec3 dr;
  if (options_.frame == TranslationFrame::Old) {
    dr = rot_old * X;
  } else {
    const Quat half = options_.rotation == RotationComposition::ExponentialMap ? quat_from_rotation_vector(0.5 * theta)
                                                                                : Quat::Identity().slerp(0.5, dq);
    dr = (q_old * half).normalized().toRotationMatrix() * X;
  }
  Vec3 r = p.position(ui) + dr;
  Int3 image = p.image(ui);
  state_.box.wrap(r, image);

  const bool field = field_on_ && field_.active();
  const bool dipole = field_on_ && ewald_ && dipoles_.species_carries[us];
  const double u = (field || dipole) ? rng_.uniform() : 0.0;
  if (overlap_.overlaps(i, r, rot_new)) return;
  ++c.passed;
  const double dU_field = field ? field_.energy(rot_new) - field_.energy(rot_old) : 0.0;
  const double dU_dipole = dipole ? ewald_->delta_energy(p, ui, r) : 0.0;
  if (!metropolis(dU_field + dU_dipole, u)) return;
  if (dipole) {
    ewald_->accept(ui);
    dipolar_energy_ += dU_dipole;
  }
  ++c.accepted;
  for (int k = 0; k < 3; ++k) {
    body_displacement_[3 * ui + static_cast<std::size_t>(k)] += X[k];
    body_rotation_[3 * ui + static_cast<std::size_t>(k)] += theta[k];
  }
  accumulate_rotation_vectors(ui, rot_old, rot_new);
  commit(i, r, image, q_new, rot_new);
}

void DmcEngine::translation(std::int32_t i, int s, TrialCounts& c) {
  const auto ui = static_cast<std::size_t>(i);
  const auto us = static_cast<std::size_t>(s);
  Particles& p = state_.particles;
  const Vec3 X = uniform_in_box(rng_, translate_cap_[us]);
  Vec3 r = p.position(ui) + X;
  Int3 image = p.image(ui);
  state_.box.wrap(r, image);
  const bool dipole = field_on_ && ewald_ && dipoles_.species_carries[us];
  const double u = dipole ? rng_.uniform() : 0.0;
  const Mat3& rot = overlap_.rotation(i);
  if (overlap_.overlaps(i, r, rot)) return;
  ++c.passed;
  if (dipole) {
    const double dU = ewald_->delta_energy(p, ui, r);
    if (!metropolis(dU, u)) return;
    ewald_->accept(ui);
    dipolar_energy_ += dU;
  }
  ++c.accepted;
  for (int k = 0; k < 3; ++k) body_displacement_[3 * ui + static_cast<std::size_t>(k)] += X[k];
  commit(i, r, image, p.orientation(ui), rot);
}

void DmcEngine::tracer_move(std::int32_t i, int s, TrialCounts& c) {
  const auto ui = static_cast<std::size_t>(i);
  const auto us = static_cast<std::size_t>(s);
  Particles& p = state_.particles;
  Vec3 half = translate_cap_[us];
  half[tracer_.axis] = tracer_parallel_step();
  const Vec3 X = uniform_in_box(rng_, half);
  Vec3 r = p.position(ui) + X;
  Int3 image = p.image(ui);
  state_.box.wrap(r, image);
  const double u = rng_.uniform();
  const Mat3& rot = overlap_.rotation(i);
  if (overlap_.overlaps(i, r, rot)) return;
  ++c.passed;
  // βΔU = −βF Δz, with Δz the increment of the unwrapped coordinate along the force.
  if (!metropolis(-tracer_.beta_force * X[tracer_.axis], u)) return;
  ++c.accepted;
  for (int k = 0; k < 3; ++k) body_displacement_[3 * ui + static_cast<std::size_t>(k)] += X[k];
  commit(i, r, image, p.orientation(ui), rot);
}

void DmcEngine::reset_accumulators() {
  std::fill(body_displacement_.begin(), body_displacement_.end(), 0.0);
  std::fill(body_rotation_.begin(), body_rotation_.end(), 0.0);
  std::fill(rotation_vector_.begin(), rotation_vector_.end(), 0.0);
}

void DmcEngine::commit(std::int32_t i, const Vec3& r, const Int3& image, const Quat& q, const Mat3& rot_new) {
  Particles& p = state_.particles;
  const auto ui = static_cast<std::size_t>(i);
  p.set_position(ui, r);
  p.set_image(ui, image);
  p.set_orientation(ui, q);
  overlap_.moved(i, r, rot_new);
}

void DmcEngine::accumulate_rotation_vectors(std::size_t i, const Mat3& old_rot, const Mat3& new_rot) {
  // δφ = (λ_old × λ_new)/|λ_old × λ_new| · angle(λ_old, λ_new) for each body axis λ (spec 10 §4.6);
  // atan2 keeps the angle accurate for the tiny rotations of a DMC step.
  for (int k = 0; k < 3; ++k) {
    const Vec3 a = old_rot.col(k), b = new_rot.col(k);
    const Vec3 cross = a.cross(b);
    const double sine = cross.norm();
    if (sine == 0.0) continue;
    const Vec3 dphi = cross * (std::atan2(sine, a.dot(b)) / sine);
    for (int d = 0; d < 3; ++d) rotation_vector_[9 * i + static_cast<std::size_t>(3 * k + d)] += dphi[d];
  }
}

double DmcEngine::field_energy() const {
  if (!field_on_ || !field_.active()) return 0.0;
  double u = 0.0;
  for (std::size_t i = 0; i < state_.particles.size(); ++i)
    if (anisotropic_[static_cast<std::size_t>(state_.particles.species[i])])
      u += field_.energy(overlap_.rotation(static_cast<std::int32_t>(i)));
  return u;
}

nlohmann::json DmcEngine::checkpoint() const {
  const RngState& r = rng_.state();
  nlohmann::json j{{"rng", {r.seed, r.stream, r.counter, r.used}},
                   {"time_steps", dt_},
                   {"field_on", field_on_},
                   {"field_direction", {field_.direction.x(), field_.direction.y(), field_.direction.z()}},
                   {"body_displacement", body_displacement_},
                   {"body_rotation", body_rotation_},
                   {"rotation_vector", rotation_vector_}};
  if (ewald_ && field_on_) {
    j["structure_factor"] = ewald_->structure_factor();
    j["dipolar_energy"] = dipolar_energy_;
  }
  return j;
}

void DmcEngine::restore(const nlohmann::json& j) {
  const auto r = j.at("rng");
  rng_ = Rng(RngState{r[0].get<std::uint64_t>(), r[1].get<std::uint64_t>(), r[2].get<std::uint64_t>(), r[3].get<std::uint32_t>()});
  set_time_steps(j.at("time_steps").get<std::vector<double>>());
  const auto d = j.at("field_direction");
  field_.direction = Vec3(d[0].get<double>(), d[1].get<double>(), d[2].get<double>());
  body_displacement_ = j.at("body_displacement").get<std::vector<double>>();
  body_rotation_ = j.at("body_rotation").get<std::vector<double>>();
  rotation_vector_ = j.at("rotation_vector").get<std::vector<double>>();
  field_on_ = j.at("field_on").get<bool>();
  if (ewald_ && field_on_) {
    // The incrementally updated S(k) differs in the last bits from a rebuild: restore it exactly.
    ewald_->set_structure_factor(j.at("structure_factor").get<std::vector<double>>());
    dipolar_energy_ = j.at("dipolar_energy").get<double>();
  }
}

}  // namespace anisodyn

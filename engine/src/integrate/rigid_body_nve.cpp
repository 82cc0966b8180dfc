#include "anisodyn/integrate/rigid_body_nve.hpp"

#include <cmath>
#include <string>
#include <utility>

#include "anisodyn/core/error.hpp"
#include "anisodyn/core/quaternion.hpp"

namespace anisodyn {

namespace {

using Vec4 = Eigen::Vector4d;  // a quaternion, or its conjugate momentum, as (w, x, y, z)

/// P_k x = x ⊗ e_k, the Hamilton product with body axis k's unit quaternion (k = 0, 1, 2 for the
/// paper's P_1, P_2, P_3). These are the columns 1–3 of S(x); column 0 is x itself.
Vec4 permute(int k, const Vec4& x) {
  switch (k) {
    case 0: return Vec4(-x[1], x[0], x[3], -x[2]);
    case 1: return Vec4(-x[2], -x[3], x[0], x[1]);
    default: return Vec4(-x[3], x[2], -x[1], x[0]);
  }
}

/// R_k(t): the exact flow over time t of the rotor about body axis k alone,
/// H_k = (pᵀ P_k q)² / (8 I_k), under which pᵀ P_k q = 2 L_body,k is constant.
void rotate_about(int k, double t, double moment, Vec4& q, Vec4& p) {
  const Vec4 pk_q = permute(k, q);
  const double zeta = t * p.dot(pk_q) / (4.0 * moment);
  const double c = std::cos(zeta), s = std::sin(zeta);
  p = c * p + s * permute(k, p);
  q = c * q + s * pk_q;
}

/// L without its components along the body axes of zero moment. Subtracting the components (rather
/// than a round trip through the body frame) changes an L that has none by no more than they are.
Vec3 without_frozen_axes(const Vec3& moments, const Quat& q, Vec3 L) {
  if (moments.minCoeff() > 0.0) return L;
  if (moments.maxCoeff() == 0.0) return Vec3::Zero();
  const Mat3 rot = q.toRotationMatrix();
  for (int k = 0; k < 3; ++k)
    if (moments[k] == 0.0) L -= L.dot(rot.col(k)) * rot.col(k);
  return L;
}

/// A linear rotor: one zero moment, the other two equal (a rod of sites on one body axis).
bool is_linear_rotor(const Vec3& m) {
  for (int k = 0; k < 3; ++k)
    if (m[k] == 0.0 && m[(k + 1) % 3] > 0.0 && m[(k + 1) % 3] == m[(k + 2) % 3]) return true;
  return false;
}

/// The free rotation R3(dt/2) R2(dt/2) R1(dt) R2(dt/2) R3(dt/2) of orientation q with lab-frame
/// angular momentum L. Each R_k is the flow of a Hamiltonian that is invariant under rotations of
/// the lab, so it keeps the lab-frame L exactly: only q changes, and L is never converted back
/// from p (the round trip lab → body → lab would change it by a few ε each step). Axes with zero
/// moment neither rotate nor keep angular momentum: L loses its components along them before
/// and after the rotation.
void rotate_freely(const Vec3& moments, double dt, Quat& q, Vec3& L) {
  if (moments.maxCoeff() == 0.0) {
    L.setZero();
    return;
  }
  L = without_frozen_axes(moments, q, L);
  if (is_linear_rotor(moments)) {
    // The exact free flow (spec 30 §3.2), which the splitting would only approximate: with
    // L ⊥ û the angular velocity is L / I⊥, constant, and the rod turns about it by |L| dt / I⊥.
    q = rotate_in_lab_frame(q, (dt / moments.maxCoeff()) * L);
    return;
  }
  Vec4 qv(q.w(), q.x(), q.y(), q.z());
  const Vec3 body = q.toRotationMatrix().transpose() * L;
  Vec4 p = Vec4::Zero();  // p = 2 S(q) (0, L_body): column k of S(q) is P_k q
  for (int k = 0; k < 3; ++k)
    if (moments[k] > 0.0) p += 2.0 * body[k] * permute(k, qv);
  static constexpr int kAxis[5] = {2, 1, 0, 1, 2};
  static constexpr double kFraction[5] = {0.5, 0.5, 1.0, 0.5, 0.5};
  for (int m = 0; m < 5; ++m)
    if (moments[kAxis[m]] > 0.0) rotate_about(kAxis[m], kFraction[m] * dt, moments[kAxis[m]], qv, p);
  // The exact maps keep |q| = 1; this removes the round-off, which would otherwise walk away from 1.
  qv.normalize();
  q = Quat(qv[0], qv[1], qv[2], qv[3]);
  L = without_frozen_axes(moments, q, L);
}

}  // namespace

RigidBodyNve::RigidBodyNve(double dt, std::vector<BodyInertia> inertia, ForceField force_field, ThermostatHook thermostat)
    : dt_(dt), inertia_(std::move(inertia)), force_field_(std::move(force_field)), thermostat_(std::move(thermostat)) {
  if (!(dt_ > 0.0) || !std::isfinite(dt_)) throw InputError("RigidBodyNve: the time step must be positive and finite");
  if (!force_field_) throw InputError("RigidBodyNve: no force field");
  for (std::size_t s = 0; s < inertia_.size(); ++s) {
    const BodyInertia& b = inertia_[s];
    if (!(b.mass > 0.0) || !std::isfinite(b.mass))
      throw InputError("RigidBodyNve: species " + std::to_string(s) + ": the mass must be positive and finite");
    if (!(b.principal_moments.minCoeff() >= 0.0) || !b.principal_moments.allFinite())
      throw InputError("RigidBodyNve: species " + std::to_string(s) + ": the principal moments must be zero or positive and finite");
  }
}

bool RigidBodyNve::any_rotating_species() const {
  for (const BodyInertia& b : inertia_)
    if (b.principal_moments.maxCoeff() > 0.0) return true;
  return false;
}

void RigidBodyNve::restore_forces(BodyForces forces) {
  if (forces.force.size() != forces.torque.size())
    throw InputError("RigidBodyNve::restore_forces: as many forces as torques needed");
  forces_ = std::move(forces);
  have_forces_ = true;
}

void RigidBodyNve::check_species(const Particles& p) const {
  // Every step, so in parallel (a serial loop here left the other thread idle: docs/performance.md).
  const auto species = static_cast<std::int64_t>(inertia_.size());
  std::size_t first_bad = p.size();
#pragma omp parallel for schedule(static) reduction(min : first_bad) if (p.size() >= kParallelBodies)
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.species[i] < 0 || p.species[i] >= species) first_bad = std::min(first_bad, i);
  if (first_bad < p.size()) {
    const std::size_t i = first_bad;
    throw InputError("RigidBodyNve: particle " + std::to_string(i) + " is of species " + std::to_string(p.species[i]) +
                       ", but inertia is given for " + std::to_string(inertia_.size()) + " species");
  }
}

void RigidBodyNve::evaluate_forces(const State& state) {
  const std::size_t n = state.particles.size();
  forces_.reset(n);
  force_field_(state, forces_);
  if (forces_.force.size() != n || forces_.torque.size() != n)
    throw RuntimeFailure("RigidBodyNve: the force field changed the number of bodies");
  have_forces_ = true;
}

void RigidBodyNve::evaluate_forces_predicted(State& state) {
  Particles& p = state.particles;
  const std::size_t n = p.size();
  const bool angular = p.has_angular_momenta();
  const double ahead = (lambda_ - 0.5) * dt_;  // forces_ still holds F(t)
  half_step_v_.resize(n);
  half_step_l_.resize(angular ? n : 0);
#pragma omp parallel for schedule(static) if (n >= kParallelBodies)
  for (std::size_t i = 0; i < n; ++i) {
    const BodyInertia& b = inertia_[static_cast<std::size_t>(p.species[i])];
    half_step_v_[i] = p.velocity(i);
    if (angular) half_step_l_[i] = p.angular_momentum(i);
    if (b.fixed) continue;
    p.set_velocity(i, half_step_v_[i] + (ahead / b.mass) * forces_.force[i]);
    if (angular)
      p.set_angular_momentum(i, without_frozen_axes(b.principal_moments, p.orientation(i), half_step_l_[i] + ahead * forces_.torque[i]));
  }
  evaluate_forces(state);
#pragma omp parallel for schedule(static) if (n >= kParallelBodies)
  for (std::size_t i = 0; i < n; ++i) {
    p.set_velocity(i, half_step_v_[i]);
    if (angular) p.set_angular_momentum(i, half_step_l_[i]);
  }
}

double RigidBodyNve::step(State& state) {
  Particles& p = state.particles;
  if (!p.has_velocities()) p.carry_velocities();
  // Point bodies (a DPD liquid) neither rotate nor need angular momenta: a state of them alone
  // is not given any, so its frames stay velocities only.
  if (!p.has_angular_momenta() && any_rotating_species()) p.carry_angular_momenta();
  const bool angular = p.has_angular_momenta();
  check_species(p);
  const std::size_t n = p.size();
  if (!have_forces_) evaluate_forces(state);
  if (forces_.force.size() != n)
    throw RuntimeFailure("RigidBodyNve: the carried forces are for " + std::to_string(forces_.force.size()) +
                         " bodies, the state has " + std::to_string(n) + " (invalidate_forces() after changing the state)");
  const double half = 0.5 * dt_;
  const Box& box = state.box;

  // Half kick, drift, free rotation.
#pragma omp parallel for schedule(static) if (n >= kParallelBodies)
  for (std::size_t i = 0; i < n; ++i) {
    const BodyInertia& b = inertia_[static_cast<std::size_t>(p.species[i])];
    if (b.fixed) continue;
    const Vec3 v = p.velocity(i) + (half / b.mass) * forces_.force[i];
    Vec3 r = p.position(i) + dt_ * v;
    Int3 image = p.image(i);
    box.wrap(r, image);
    p.set_velocity(i, v);
    p.set_position(i, r);
    p.set_image(i, image);
    if (!angular) continue;
    Quat q = p.orientation(i);
    Vec3 L = p.angular_momentum(i) + half * forces_.torque[i];
    rotate_freely(b.principal_moments, dt_, q, L);
    p.set_orientation(i, q);
    p.set_angular_momentum(i, L);
  }

  // Forces of the new configuration (with the half-step momenta in the state, or the predicted
  // ones), then the second half kick.
  if (lambda_ == 0.5) evaluate_forces(state);
  else evaluate_forces_predicted(state);
#pragma omp parallel for schedule(static) if (n >= kParallelBodies)
  for (std::size_t i = 0; i < n; ++i) {
    const BodyInertia& b = inertia_[static_cast<std::size_t>(p.species[i])];
    if (b.fixed) continue;
    p.set_velocity(i, p.velocity(i) + (half / b.mass) * forces_.force[i]);
    if (!angular) continue;
    p.set_angular_momentum(i, without_frozen_axes(b.principal_moments, p.orientation(i),
                                                  p.angular_momentum(i) + half * forces_.torque[i]));
  }

  if (thermostat_) thermostat_(state, dt_);
  return dt_;
}

}  // namespace anisodyn

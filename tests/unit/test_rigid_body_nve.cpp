// RigidBodyNve (integrate/rigid_body_nve.hpp): velocity Verlet + NO_SQUISH against references
// that do not use it:
// - free asymmetric top: energy error of second order (halving dt divides it by about 4) and the
//   lab angular momentum kept to round-off; orientation against a fine fourth-order Runge–Kutta
//   integration of Euler's equations, also of second order;
// - free symmetric top against the closed-form Euler solution (ω3 constant, (ω1, ω2) turning at
//   (I3 − I1)/I1 ω3) and the precession of its symmetry axis about L at |L|/I1;
// - linear rotor (one zero moment): the rod axis turns about L exactly;
// - bodies of sites in harmonic site fields: each body's energy conserved with a second-order
//   error and no drift; time reversal returns to the start;
// - free translation: constant velocities, wrapped positions and image counters;
// - restart: a fresh integrator on a copy of the state continues bit for bit (and, for a
//   velocity-dependent force field, with the carried forces restored);
// - the same bits with 1 and 2 threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "anisodyn/core/error.hpp"
#include "anisodyn/core/keyed_random.hpp"
#include "anisodyn/core/quaternion.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/integrate/rigid_body_nve.hpp"
#include "anisodyn/system/rigid_sites.hpp"
#include "thread_count.hpp"

using namespace anisodyn;

namespace {

const ForceField kNoForces = [](const State&, BodyForces&) {};

/// What a runner does: step, then count the step and its time.
void run(Integrator& integrator, State& state, int steps) {
  for (int n = 0; n < steps; ++n) {
    state.time += integrator.step(state);
    ++state.step;
  }
}

/// A state of one body of species 0 in a large box.
State one_body(const Quat& q, const Vec3& angular_momentum, const Vec3& velocity = Vec3::Zero()) {
  State s;
  s.box = Box(Vec3::Constant(50));
  s.particles.carry_velocities();
  s.particles.carry_angular_momenta();
  s.particles.add(0, Vec3::Constant(25), q, 0);
  s.particles.set_angular_momentum(0, angular_momentum);
  s.particles.set_velocity(0, velocity);
  return s;
}

/// Body-frame angular momentum of body i.
Vec3 body_momentum(const Particles& p, std::size_t i) {
  return p.orientation(i).toRotationMatrix().transpose() * p.angular_momentum(i);
}

/// Σ_k L_k² / (2 I_k) over the axes with a moment.
double rotational_energy(const Particles& p, std::size_t i, const Vec3& moments) {
  const Vec3 b = body_momentum(p, i);
  double e = 0;
  for (int k = 0; k < 3; ++k)
    if (moments[k] > 0) e += b[k] * b[k] / (2 * moments[k]);
  return e;
}

/// Rotation by angle about a unit axis (Rodrigues), independent of the quaternion code.
Vec3 rotated(const Vec3& v, const Vec3& axis, double angle) {
  return v * std::cos(angle) + axis.cross(v) * std::sin(angle) + axis * axis.dot(v) * (1 - std::cos(angle));
}

// ---- the free rigid body by RK4 on Euler's equations and dq/dt = ½ q ⊗ (0, ω_body) -------------

struct TopState {
  Eigen::Vector4d q;  // (w, x, y, z)
  Vec3 L;             // body frame
};

TopState top_rate(const TopState& s, const Vec3& I) {
  const Vec3 w = s.L.cwiseQuotient(I);
  const Quat q(s.q[0], s.q[1], s.q[2], s.q[3]);
  const Quat dq = q * Quat(0, w.x(), w.y(), w.z());
  return {0.5 * Eigen::Vector4d(dq.w(), dq.x(), dq.y(), dq.z()), s.L.cross(w)};  // dL/dt = L × ω in the body frame
}

TopState rk4_top(TopState s, const Vec3& I, double T, int steps) {
  const double h = T / steps;
  auto plus = [](const TopState& a, const TopState& d, double f) { return TopState{a.q + f * d.q, a.L + f * d.L}; };
  for (int n = 0; n < steps; ++n) {
    const TopState k1 = top_rate(s, I), k2 = top_rate(plus(s, k1, h / 2), I), k3 = top_rate(plus(s, k2, h / 2), I),
                   k4 = top_rate(plus(s, k3, h), I);
    s.q += h / 6 * (k1.q + 2 * k2.q + 2 * k3.q + k4.q);
    s.L += h / 6 * (k1.L + 2 * k2.L + 2 * k3.L + k4.L);
    s.q.normalize();
  }
  return s;
}

Mat3 rotation_of(const Eigen::Vector4d& q) { return Quat(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix(); }

// ---- bodies of sites in harmonic site fields -----------------------------------------------------

/// Three kinds of body: an asymmetric body of six sites (three distinct moments), a linear rod of
/// five sites on body z (moments (I⊥, I⊥, 0)) and a point particle (no rotation).
struct SiteSystem {
  SiteTable sites;
  std::vector<BodyInertia> inertia;
  std::vector<std::vector<Vec3>> anchors;  // per body, per site
  double k = 1.0;

  SiteSystem() {
    SiteBody asym, rod, point;
    asym.offsets = {Vec3(0.5, 0, 0), Vec3(-0.5, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1.5), Vec3(0, 0, -1.5)};
    for (int j = -2; j <= 2; ++j) rod.offsets.emplace_back(0, 0, 0.5 * j);
    point.offsets = {Vec3::Zero()};
    sites = {asym, rod, point};
    const double site_mass = 0.8;
    for (const SiteBody& b : sites)
      inertia.push_back({site_mass * static_cast<double>(b.size()), point_mass_moments(b.offsets, site_mass)});
  }

  /// Unwrapped lab positions of body i's sites.
  std::vector<Vec3> site_positions_of(const State& s, std::size_t i) const {
    const SiteBody& body = sites[static_cast<std::size_t>(s.particles.species[i])];
    std::vector<Vec3> r(body.size());
    site_positions(body, s.box.unwrap(s.particles.position(i), s.particles.image(i)), s.particles.orientation(i), r);
    return r;
  }

  /// U_i = Σ_s ½ k |r_s − a_s|².
  double potential(const State& s, std::size_t i) const {
    const auto r = site_positions_of(s, i);
    double u = 0;
    for (std::size_t j = 0; j < r.size(); ++j) u += 0.5 * k * (r[j] - anchors[i][j]).squaredNorm();
    return u;
  }

  double energy(const State& s, std::size_t i) const {
    const BodyInertia& b = inertia[static_cast<std::size_t>(s.particles.species[i])];
    return potential(s, i) + 0.5 * b.mass * s.particles.velocity(i).squaredNorm() +
           rotational_energy(s.particles, i, b.principal_moments);
  }

  ForceField field() const {
    return [this](const State& s, BodyForces& out) {
      for (std::size_t i = 0; i < s.particles.size(); ++i) {
        const auto r = site_positions_of(s, i);
        std::vector<Vec3> f(r.size());
        for (std::size_t j = 0; j < r.size(); ++j) f[j] = -k * (r[j] - anchors[i][j]);
        const Wrench w = reduce_site_forces(sites[static_cast<std::size_t>(s.particles.species[i])], s.particles.orientation(i), f);
        out.force[i] += w.force;
        out.torque[i] += w.torque;
        out.energy += potential(s, i);
      }
    };
  }

  /// Two bodies of each kind near the box edges (so that they cross it), each with its own anchors
  /// near its start, random velocities and angular momenta.
  State make_state(std::uint64_t seed) {
    Rng rng(seed, 7);
    State s;
    s.box = Box(Vec3(6, 7, 8));
    s.particles.carry_velocities();
    s.particles.carry_angular_momenta();
    anchors.clear();
    for (int n = 0; n < 6; ++n) {
      const int species = n % 3;
      const SiteBody& body = sites[static_cast<std::size_t>(species)];
      Vec3 r(rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3), rng.uniform(0, 8));
      Int3 image(0, 0, 0);
      const Vec3 centre = r;
      s.box.wrap(r, image);
      const Quat q = uniform_quaternion(rng.uniform(), rng.uniform(), rng.uniform());
      const std::size_t i = s.particles.size();
      s.particles.add(species, r, q, 100 + n);
      s.particles.set_image(i, image);
      // Anchors: the sites as placed, turned a little and shifted, so that the body starts off
      // equilibrium in position and orientation.
      const Quat turned = rotate_in_lab_frame(q, Vec3(rng.uniform(-0.4, 0.4), rng.uniform(-0.4, 0.4), rng.uniform(-0.4, 0.4)));
      std::vector<Vec3> a(body.size());
      site_positions(body, centre + Vec3(rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2)), turned, a);
      anchors.push_back(a);
      s.particles.set_velocity(i, Vec3(rng.normal(), rng.normal(), rng.normal()));
      Vec3 L(rng.normal(), rng.normal(), rng.normal());
      if (species == 1) L -= L.dot(q * Vec3::UnitZ()) * (q * Vec3::UnitZ());  // a rod's L is ⊥ û
      if (species == 2) L.setZero();
      s.particles.set_angular_momentum(i, 2.0 * L);
    }
    return s;
  }
};

/// Name of the first field in which two particle sets differ bit for bit ("" when none does).
std::string first_difference(const Particles& a, const Particles& b) {
  if (a.x != b.x || a.y != b.y || a.z != b.z) return "position";
  if (a.ix != b.ix || a.iy != b.iy || a.iz != b.iz) return "image";
  if (a.qw != b.qw || a.qx != b.qx || a.qy != b.qy || a.qz != b.qz) return "orientation";
  if (a.vx != b.vx || a.vy != b.vy || a.vz != b.vz) return "velocity";
  if (a.lx != b.lx || a.ly != b.ly || a.lz != b.lz) return "angular momentum";
  if (a.species != b.species || a.id != b.id) return "species or id";
  return "";
}

}  // namespace

TEST(RigidBodyNve, FreeAsymmetricTopKeepsEnergyToSecondOrderAndAngularMomentumExactly) {
  const Vec3 I(1, 2, 3);
  const Quat q0 = uniform_quaternion(0.3, 0.7, 0.2);
  const Vec3 L0(0.7, -1.1, 0.4);
  const double T = 20;
  std::vector<double> energy_error;
  for (const double dt : {0.02, 0.01, 0.005}) {
    State s = one_body(q0, L0);
    RigidBodyNve nve(dt, {{1.0, I}}, kNoForces);
    const double e0 = rotational_energy(s.particles, 0, I);
    double de = 0, dl = 0;
    for (int n = 0; n < std::lround(T / dt); ++n) {
      run(nve, s, 1);
      de = std::max(de, std::abs(rotational_energy(s.particles, 0, I) - e0));
      dl = std::max(dl, (s.particles.angular_momentum(0) - L0).norm());
    }
    EXPECT_EQ(dl, 0.0) << "dt = " << dt << ": the free rotation keeps the lab L to the last bit";
    EXPECT_LT(std::abs(s.particles.orientation(0).norm() - 1.0), 1e-13) << "NO_SQUISH keeps |q| = 1";
    EXPECT_LT(de / e0, 0.1 * dt * dt) << "dt = " << dt;
    energy_error.push_back(de / e0);
    std::printf("free asymmetric top, dt = %g: max |ΔE|/E = %.3e, max |ΔL| = %.1e\n", dt, de / e0, dl);
  }
  for (std::size_t m = 0; m + 1 < energy_error.size(); ++m) {
    const double ratio = energy_error[m] / energy_error[m + 1];
    std::printf("  energy error ratio for dt → dt/2: %.3f\n", ratio);
    EXPECT_GT(ratio, 3.6);
    EXPECT_LT(ratio, 4.4);
  }
}

TEST(RigidBodyNve, FreeAsymmetricTopOrientationConvergesAtSecondOrder) {
  const Vec3 I(1, 2, 3);
  const Quat q0 = uniform_quaternion(0.8, 0.1, 0.55);
  const Vec3 L0_body(0.9, 0.3, -1.2);
  const double T = 10;
  const TopState start{Eigen::Vector4d(q0.w(), q0.x(), q0.y(), q0.z()), L0_body};
  const TopState ref = rk4_top(start, I, T, 100000);
  const TopState ref_coarse = rk4_top(start, I, T, 50000);
  ASSERT_LT((rotation_of(ref.q) - rotation_of(ref_coarse.q)).norm(), 1e-11) << "the reference is converged";

  std::vector<double> error;
  for (const double dt : {0.02, 0.01, 0.005}) {
    State s = one_body(q0, q0 * L0_body);
    RigidBodyNve nve(dt, {{1.0, I}}, kNoForces);
    run(nve, s, static_cast<int>(std::lround(T / dt)));
    const double e = (s.particles.orientation(0).toRotationMatrix() - rotation_of(ref.q)).norm() +
                     (body_momentum(s.particles, 0) - ref.L).norm();
    error.push_back(e);
    std::printf("asymmetric top vs RK4 at t = %g, dt = %g: error %.3e\n", T, dt, e);
  }
  for (std::size_t m = 0; m + 1 < error.size(); ++m) {
    std::printf("  ratio for dt → dt/2: %.3f\n", error[m] / error[m + 1]);
    EXPECT_GT(error[m] / error[m + 1], 3.6);
    EXPECT_LT(error[m] / error[m + 1], 4.4);
  }
  EXPECT_LT(error.back(), 1e-3);
}

TEST(RigidBodyNve, FreeSymmetricTopFollowsTheEulerSolution) {
  const Vec3 I(2, 2, 3);
  const Vec3 w0(0.6, -0.2, 1.5);  // body-frame angular velocity at t = 0
  const Quat q0 = uniform_quaternion(0.45, 0.9, 0.05);
  const Vec3 L_lab = q0 * I.cwiseProduct(w0);
  const double Omega = (I[2] - I[0]) / I[0] * w0[2];
  const Vec3 axis0 = q0 * Vec3::UnitZ(), L_hat = L_lab.normalized();
  const double precession = L_lab.norm() / I[0];

  std::vector<double> error;
  for (const double dt : {0.01, 0.005}) {
    State s = one_body(q0, L_lab);
    RigidBodyNve nve(dt, {{1.0, I}}, kNoForces);
    const int steps = static_cast<int>(std::lround(50 / dt)), every = steps / 10;
    double worst = 0, worst_axis = 0;
    for (int n = every; n <= steps; n += every) {
      run(nve, s, every);
      const double t = n * dt;
      const Vec3 exact(w0[0] * std::cos(Omega * t) - w0[1] * std::sin(Omega * t),
                       w0[0] * std::sin(Omega * t) + w0[1] * std::cos(Omega * t), w0[2]);
      worst = std::max(worst, (body_momentum(s.particles, 0).cwiseQuotient(I) - exact).norm());
      worst_axis = std::max(worst_axis, (s.particles.orientation(0) * Vec3::UnitZ() - rotated(axis0, L_hat, precession * t)).norm());
    }
    std::printf("symmetric top to t = 50 (%d steps), dt = %g: max |ω − ω_exact| = %.3e, max symmetry-axis error %.3e\n",
                steps, dt, worst, worst_axis);
    EXPECT_LT(worst, 2e-3 * w0.norm());
    EXPECT_LT(worst_axis, 2e-3);
    error.push_back(worst);
  }
  std::printf("  ratio for dt → dt/2: %.3f\n", error[0] / error[1]);
  EXPECT_GT(error[0] / error[1], 3.6);
  EXPECT_LT(error[0] / error[1], 4.4);
}

TEST(RigidBodyNve, LinearRotorTurnsAboutItsAngularMomentum) {
  // Moments (I⊥, I⊥, 0): û = body z. A component of L along û is dropped.
  const Vec3 I(1.5, 1.5, 0);
  const Quat q0 = uniform_quaternion(0.2, 0.4, 0.6);
  const Vec3 u0 = q0 * Vec3::UnitZ();
  const Vec3 L_perp = Vec3(0.3, -0.8, 0.5) - Vec3(0.3, -0.8, 0.5).dot(u0) * u0;
  State s = one_body(q0, L_perp + 0.7 * u0);
  const double dt = 0.01;
  RigidBodyNve nve(dt, {{1.0, I}}, kNoForces);
  const int steps = 5000;
  run(nve, s, steps);
  const Vec3 u = s.particles.orientation(0) * Vec3::UnitZ();
  const Vec3 exact = rotated(u0, L_perp.normalized(), L_perp.norm() / I[0] * steps * dt);
  std::printf("linear rotor after %d steps: |û − û_exact| = %.2e\n", steps, (u - exact).norm());
  EXPECT_LT((u - exact).norm(), 1e-12);
  EXPECT_LT((s.particles.angular_momentum(0) - L_perp).norm(), 1e-13);
  EXPECT_LT(std::abs(s.particles.angular_momentum(0).dot(u)), 1e-13);
}

TEST(RigidBodyNve, BodiesOfSitesInHarmonicFieldsConserveEnergyToSecondOrder) {
  SiteSystem sys;
  const State start = sys.make_state(11);
  const double T = 100;
  const char* kind[3] = {"asymmetric body", "linear rod", "point particle"};
  std::vector<std::vector<double>> error(start.particles.size());
  for (const double dt : {0.01, 0.005}) {
    State s = start;
    RigidBodyNve nve(dt, sys.inertia, sys.field());
    std::vector<double> e0(s.particles.size()), de(s.particles.size(), 0.0), first(s.particles.size(), 0.0),
        last(s.particles.size(), 0.0);
    for (std::size_t i = 0; i < s.particles.size(); ++i) e0[i] = sys.energy(s, i);
    const int steps = static_cast<int>(std::lround(T / dt)), tenth = steps / 10;
    for (int n = 1; n <= steps; ++n) {
      run(nve, s, 1);
      for (std::size_t i = 0; i < s.particles.size(); ++i) {
        const double d = sys.energy(s, i) - e0[i];
        de[i] = std::max(de[i], std::abs(d));
        if (n <= tenth) first[i] += d / tenth;
        if (n > steps - tenth) last[i] += d / tenth;
      }
    }
    for (std::size_t i = 0; i < s.particles.size(); ++i) {
      const int species = s.particles.species[i];
      std::printf("%s %zu, dt = %g, %d steps: E = %.4f, max |ΔE|/E = %.3e, drift (mean ΔE last − first tenth)/E = %.1e\n",
                  kind[species], i, dt, steps, e0[i], de[i] / e0[i], (last[i] - first[i]) / e0[i]);
      error[i].push_back(de[i]);
      EXPECT_LT(de[i] / e0[i], 0.5 * dt * dt) << kind[species];
      EXPECT_LT(std::abs(last[i] - first[i]), 0.5 * de[i]) << kind[species] << ": energy drifts";
    }
  }
  for (std::size_t i = 0; i < error.size(); ++i) {
    const double ratio = error[i][0] / error[i][1];
    std::printf("  body %zu: energy error ratio for dt → dt/2: %.3f\n", i, ratio);
    EXPECT_GT(ratio, 3.5) << "body " << i;
    EXPECT_LT(ratio, 4.5) << "body " << i;
  }
}

TEST(RigidBodyNve, RunningBackwardsReturnsToTheStart) {
  SiteSystem sys;
  const State start = sys.make_state(23);
  State s = start;
  RigidBodyNve forward(0.01, sys.inertia, sys.field());
  run(forward, s, 2000);
  auto negate = [](State& st) {
    for (std::size_t i = 0; i < st.particles.size(); ++i) {
      st.particles.set_velocity(i, -st.particles.velocity(i));
      st.particles.set_angular_momentum(i, -st.particles.angular_momentum(i));
    }
  };
  negate(s);
  RigidBodyNve backward(0.01, sys.inertia, sys.field());
  run(backward, s, 2000);
  negate(s);
  double dr = 0, dq = 0, dv = 0, dl = 0;
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    const Vec3 r = s.box.unwrap(s.particles.position(i), s.particles.image(i));
    const Vec3 r0 = start.box.unwrap(start.particles.position(i), start.particles.image(i));
    dr = std::max(dr, (r - r0).norm());
    dq = std::max(dq, (s.particles.orientation(i).coeffs() - start.particles.orientation(i).coeffs()).norm());
    dv = std::max(dv, (s.particles.velocity(i) - start.particles.velocity(i)).norm());
    dl = std::max(dl, (s.particles.angular_momentum(i) - start.particles.angular_momentum(i)).norm());
  }
  std::printf("2000 steps forward and back: max |Δr| = %.2e, |Δq| = %.2e, |Δv| = %.2e, |ΔL| = %.2e\n", dr, dq, dv, dl);
  EXPECT_LT(dr, 1e-12);
  EXPECT_LT(dq, 1e-12);
  EXPECT_LT(dv, 1e-12);
  EXPECT_LT(dl, 1e-12);
}

TEST(RigidBodyNve, FreeTranslationKeepsVelocitiesAndCountsImages) {
  Rng rng(5, 1);
  State s;
  s.box = Box(Vec3(3, 4, 5));
  s.particles.carry_velocities();
  std::vector<Vec3> r0, v0;
  for (int n = 0; n < 50; ++n) {
    r0.emplace_back(rng.uniform(0, 3), rng.uniform(0, 4), rng.uniform(0, 5));
    v0.emplace_back(rng.uniform(-7, 7), rng.uniform(-7, 7), rng.uniform(-7, 7));
    s.particles.add(0, r0.back(), Quat::Identity(), n);
    s.particles.set_velocity(static_cast<std::size_t>(n), v0.back());
  }
  const double dt = 0.05;
  const int steps = 1000;
  RigidBodyNve nve(dt, {{2.0, Vec3::Zero()}}, kNoForces);
  run(nve, s, steps);
  // Point bodies only: the state is not given angular momenta (its frames stay velocities only).
  ASSERT_FALSE(s.particles.has_angular_momenta());
  double worst = 0;
  int crossings = 0;
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    const Vec3 exact = r0[i] + (steps * dt) * v0[i];
    ASSERT_EQ(s.particles.velocity(i), v0[i]);
    ASSERT_EQ(s.particles.orientation(i).coeffs(), Quat::Identity().coeffs());
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(s.particles.position(i)[a], 0.0);
      EXPECT_LT(s.particles.position(i)[a], s.box.edges()[a]);
      EXPECT_EQ(s.particles.image(i)[a], static_cast<int>(std::floor(exact[a] / s.box.edges()[a]))) << i << " " << a;
      crossings += std::abs(s.particles.image(i)[a]);
    }
    worst = std::max(worst, (s.box.unwrap(s.particles.position(i), s.particles.image(i)) - exact).norm());
  }
  std::printf("free translation: %d box crossings, max |r_unwrapped − (r0 + v t)| = %.2e\n", crossings, worst);
  EXPECT_LT(worst, 1e-11);
  EXPECT_GT(crossings, 1000);
}

TEST(RigidBodyNve, ARestartFromACopyOfTheStateContinuesBitForBit) {
  SiteSystem sys;
  const State start = sys.make_state(37);
  // A thermostat hook with keyed noise, so the hook's place in the step matters too.
  const KeyedRandom noise(2027, 9);
  int hook_calls = 0, field_calls = 0;
  const ThermostatHook langevin = [&](State& s, double dt) {
    ++hook_calls;
    const double c = std::exp(-0.5 * dt);
    for (std::size_t i = 0; i < s.particles.size(); ++i) {
      const auto id = static_cast<std::uint64_t>(s.particles.id[i]);
      const double sigma = std::sqrt((1 - c * c) / sys.inertia[static_cast<std::size_t>(s.particles.species[i])].mass);
      const Vec3 xi(noise.normal(static_cast<std::uint64_t>(s.step), id, 0, 0), noise.normal(static_cast<std::uint64_t>(s.step), id, 0, 1),
                    noise.normal(static_cast<std::uint64_t>(s.step), id, 0, 2));
      s.particles.set_velocity(i, c * s.particles.velocity(i) + sigma * xi);
      s.particles.set_angular_momentum(i, c * s.particles.angular_momentum(i));
    }
  };
  const ForceField base = sys.field();
  const ForceField counted = [&](const State& s, BodyForces& f) {
    ++field_calls;
    base(s, f);
  };
  const double dt = 0.01;
  const int n = 500;

  State continuous = start;
  RigidBodyNve one(dt, sys.inertia, counted, langevin);
  run(one, continuous, 2 * n);
  EXPECT_EQ(hook_calls, 2 * n);
  EXPECT_EQ(field_calls, 2 * n + 1) << "forces are evaluated once per step (and once before the first)";

  State first_half = start;
  RigidBodyNve before(dt, sys.inertia, base, langevin);
  run(before, first_half, n);
  State restarted = first_half;  // the checkpoint
  RigidBodyNve after(dt, sys.inertia, base, langevin);
  run(after, restarted, n);

  EXPECT_EQ(first_difference(continuous.particles, restarted.particles), "");
  EXPECT_EQ(continuous.step, restarted.step);
  EXPECT_EQ(continuous.time, restarted.time);
  EXPECT_NE(first_difference(continuous.particles, first_half.particles), "") << "the second half moved the bodies";
}

TEST(RigidBodyNve, CarriedForcesRestoreAVelocityDependentFieldExactly) {
  // A friction on every centre, −γ v: the forces of the last step used the half-step velocities,
  // which the state no longer holds, so a restart needs the carried forces.
  SiteSystem sys;
  const State start = sys.make_state(41);
  const ForceField sites = sys.field();
  const ForceField with_friction = [&](const State& s, BodyForces& f) {
    sites(s, f);
    for (std::size_t i = 0; i < s.particles.size(); ++i) f.force[i] -= 0.3 * s.particles.velocity(i);
  };
  const double dt = 0.01;
  const int n = 300;
  State continuous = start;
  RigidBodyNve one(dt, sys.inertia, with_friction);
  run(one, continuous, 2 * n);

  State checkpoint = start;
  RigidBodyNve before(dt, sys.inertia, with_friction);
  run(before, checkpoint, n);
  const BodyForces carried = before.forces();

  State restored = checkpoint, fresh = checkpoint;
  RigidBodyNve after(dt, sys.inertia, with_friction);
  after.restore_forces(carried);
  run(after, restored, n);
  EXPECT_EQ(first_difference(continuous.particles, restored.particles), "");

  RigidBodyNve forgetful(dt, sys.inertia, with_friction);
  run(forgetful, fresh, n);
  EXPECT_NE(first_difference(continuous.particles, fresh.particles), "") << "without the carried forces the runs differ";
}

TEST(RigidBodyNve, VelocityPredictionIsGrootWarrensModifiedVerlet) {
  // A spherical top (moments I) under a friction on its velocity and angular momentum, F = −γ v and
  // τ = −c L: Groot–Warren's scheme, written out, gives r, v and L of each step; the forces see
  // ṽ = v + λ δt F/m and L̃ = L + λ δt τ.
  const double m = 2.0, I = 0.7, gamma = 0.9, c = 0.4, dt = 0.05, lambda = 0.65;
  const ForceField friction = [&](const State& s, BodyForces& f) {
    f.force[0] = -gamma * s.particles.velocity(0);
    f.torque[0] = -c * s.particles.angular_momentum(0);
  };
  State s = one_body(Quat::Identity(), Vec3(0.3, -0.2, 0.5), Vec3(1.0, -0.5, 0.25));
  RigidBodyNve nve(dt, {{m, Vec3::Constant(I)}}, friction);
  nve.set_velocity_prediction(lambda);
  Vec3 r = s.particles.position(0), v = s.particles.velocity(0), L = s.particles.angular_momentum(0);
  Vec3 F = -gamma * v, T = -c * L;  // the starting forces see the starting velocities
  for (int n = 0; n < 20; ++n) {
    nve.step(s);
    r += dt * v + 0.5 * dt * dt * F / m;
    const Vec3 F_next = -gamma * (v + lambda * dt * F / m), T_next = -c * (L + lambda * dt * T);
    v += 0.5 * dt * (F + F_next) / m;
    L += 0.5 * dt * (T + T_next);
    F = F_next, T = T_next;
    ASSERT_LT((s.particles.position(0) - r).norm(), 1e-13) << n;
    ASSERT_LT((s.particles.velocity(0) - v).norm(), 1e-13) << n;
    ASSERT_LT((s.particles.angular_momentum(0) - L).norm(), 1e-13) << n;
    ASSERT_LT((nve.forces().force[0] - F).norm(), 1e-13) << n;
  }
  // λ changes the velocity-dependent forces: the plain scheme (λ = ½) ends elsewhere.
  State plain = one_body(Quat::Identity(), Vec3(0.3, -0.2, 0.5), Vec3(1.0, -0.5, 0.25));
  RigidBodyNve half(dt, {{m, Vec3::Constant(I)}}, friction);
  run(half, plain, 20);
  EXPECT_GT((plain.particles.velocity(0) - v).norm(), 1e-6);
}

TEST(RigidBodyNve, VelocityPredictionLeavesPositionOnlyForcesBitForBit) {
  // The predicted velocities are put back from a copy, so fields that do not read them give the
  // plain scheme's trajectory exactly, whatever λ.
  SiteSystem sys;
  State plain = sys.make_state(43), predicted = plain;
  RigidBodyNve a(0.01, sys.inertia, sys.field()), b(0.01, sys.inertia, sys.field());
  b.set_velocity_prediction(0.65);
  run(a, plain, 200);
  run(b, predicted, 200);
  EXPECT_EQ(first_difference(plain.particles, predicted.particles), "");
}

TEST(RigidBodyNve, ResultsDoNotDependOnTheThreadCount) {
#ifndef _OPENMP
  GTEST_SKIP() << "built without OpenMP";
#else
  // Enough bodies for the parallel loops: asymmetric tops on springs to their start.
  Rng rng(19, 4);
  State start;
  start.box = Box(Vec3::Constant(20));
  start.particles.carry_velocities();
  start.particles.carry_angular_momenta();
  for (int n = 0; n < 3000; ++n) {
    start.particles.add(0, Vec3(rng.uniform(0, 20), rng.uniform(0, 20), rng.uniform(0, 20)),
                        uniform_quaternion(rng.uniform(), rng.uniform(), rng.uniform()), n);
    start.particles.set_velocity(static_cast<std::size_t>(n), Vec3(rng.normal(), rng.normal(), rng.normal()));
    start.particles.set_angular_momentum(static_cast<std::size_t>(n), Vec3(rng.normal(), rng.normal(), rng.normal()));
  }
  const ForceField springs = [](const State& s, BodyForces& f) {
    for (std::size_t i = 0; i < s.particles.size(); ++i) {
      f.force[i] = -(s.box.unwrap(s.particles.position(i), s.particles.image(i)) - Vec3::Constant(10));
      f.torque[i] = -(s.particles.orientation(i) * Vec3::UnitZ()).cross(Vec3::UnitX());
    }
  };
  const auto advanced = [&] {
    State s = start;
    RigidBodyNve nve(0.01, {{1.5, Vec3(1, 2, 3)}}, springs);
    run(nve, s, 20);
    return s;
  };
  const State one = testing_support::with_threads(1, advanced), two = testing_support::with_threads(2, advanced);
  EXPECT_EQ(first_difference(one.particles, two.particles), "");
#endif
}

TEST(RigidBodyNve, RejectsBadInput) {
  EXPECT_THROW(RigidBodyNve(0.0, {{1.0, Vec3::Ones()}}, kNoForces), InputError);
  EXPECT_THROW(RigidBodyNve(0.01, {{0.0, Vec3::Ones()}}, kNoForces), InputError);
  EXPECT_THROW(RigidBodyNve(0.01, {{1.0, Vec3(1, -1, 1)}}, kNoForces), InputError);
  EXPECT_THROW(RigidBodyNve(0.01, {{1.0, Vec3::Ones()}}, ForceField{}), InputError);
  State s = one_body(Quat::Identity(), Vec3::Zero());
  s.particles.species[0] = 1;
  RigidBodyNve nve(0.01, {{1.0, Vec3::Ones()}}, kNoForces);
  EXPECT_THROW(nve.step(s), InputError);
  // Carried forces for another number of bodies are refused rather than used.
  s.particles.species[0] = 0;
  BodyForces two;
  two.reset(2);
  nve.restore_forces(two);
  EXPECT_THROW(nve.step(s), RuntimeFailure);
  nve.invalidate_forces();
  EXPECT_NO_THROW(nve.step(s));
}

TEST(RigidBodyNve, AFixedBodyStaysWhereItIsUnderForces) {
  // Species 1 is held fixed (spec 30 §8): a constant force and torque move species 0 but leave the
  // fixed body's position, orientation, velocity and angular momentum bit for bit as they were.
  State s;
  s.box = Box(Vec3::Constant(10.0));
  s.particles.carry_velocities();
  s.particles.carry_angular_momenta();
  const Quat q = Quat(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()));
  s.particles.add(0, Vec3(1, 2, 3), q, 0);
  s.particles.add(1, Vec3(5, 5, 5), q, 1);
  const ForceField push = [](const State& st, BodyForces& out) {
    for (std::size_t i = 0; i < st.particles.size(); ++i) {
      out.force[i] = Vec3(1.0, -0.5, 0.25);
      out.torque[i] = Vec3(0.1, 0.2, 0.3);
    }
  };
  RigidBodyNve nve(0.01, {{1.0, Vec3(1, 2, 3)}, {1.0, Vec3(1, 2, 3), true}}, push);
  run(nve, s, 200);
  EXPECT_EQ(s.particles.position(1), Vec3(5, 5, 5));
  EXPECT_EQ(s.particles.orientation(1).coeffs(), q.coeffs());
  EXPECT_EQ(s.particles.velocity(1), Vec3::Zero());
  EXPECT_EQ(s.particles.angular_momentum(1), Vec3::Zero());
  EXPECT_NEAR(s.particles.velocity(0).x(), 200 * 0.01 * 1.0, 1e-12);  // the free body: v = F t / m
}

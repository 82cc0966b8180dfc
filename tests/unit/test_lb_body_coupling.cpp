// Raspberries coupled to the LB fluid (lb/body_fluid_coupling.hpp) through RigidBodyNve: a free
// raspberry and the thermal fluid conserve their total momentum to round-off (noise on, spec 40's
// units and parameters), and a raspberry held fixed in a fluid driven by a body force takes, in
// steady state, exactly the momentum the force puts in (the units of the coupling, both ways).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "anisodyn/integrate/rigid_body_nve.hpp"
#include "anisodyn/lb/body_fluid_coupling.hpp"
#include "anisodyn/lb/raspberry.hpp"

using namespace anisodyn;
using namespace anisodyn::lb;

namespace {

constexpr double kRho = 6.004, kNu = 0.8, kXi = 0.14095 * 200.0;  // spec 40 §1: MD units; ξ scaled by s
const LbUnits kUnits{1.0, 0.01, 2};

State one_body(double box, const Vec3& velocity, const Vec3& angular_momentum) {
  State s;
  s.box = Box(Vec3::Constant(box));
  s.species = {Species{"raspberry", Shape::sphere(4.5), 1.0, {}, {}}};
  s.particles.add(0, Vec3::Constant(box / 2 + 0.3), Quat::Identity(), 0);
  s.particles.carry_velocities();
  s.particles.carry_angular_momenta();
  s.particles.set_velocity(0, velocity);
  s.particles.set_angular_momentum(0, angular_momentum);
  return s;
}

SiteTable raspberry_sites(const RaspberryGeometry& g) { return {SiteBody{g.offset, {}, {}}}; }

}  // namespace

TEST(BodyFluidCoupling, AFreeRaspberryAndTheThermalFluidConserveMomentum) {
  const Vec3 semi = Vec3::Constant(2.25);
  const RaspberryGeometry g = make_raspberry(semi);
  const double mass = raspberry_mass(semi, kRho);
  const Vec3 moments = raspberry_moments(semi, mass);
  const int edge = 12;
  LbFluid fluid({edge, edge, edge}, LbParameters{kRho, kNu * kUnits.lb_time_step(), 0.0, 0.0, 1.0 * kUnits.energy_to_lattice(), 5});
  BodyFluidCoupling coupling(fluid, raspberry_sites(g), {moments}, kXi, 1.0, 9, kUnits);
  RigidBodyNve nve(kUnits.md_time_step, {{mass, moments}}, [&](const State& st, BodyForces& out) { coupling(st, out); },
                   [&](State& st, double dt) { coupling.after_step(st, dt); });
  State s = one_body(edge, Vec3(0.05, -0.02, 0.01), Vec3(3.0, 1.0, -2.0));
  const auto total = [&]() -> Vec3 { return mass * s.particles.velocity(0) + coupling.fluid_momentum(); };
  const Vec3 before = total();
  // Velocity Verlet gives the starting forces F₀ to the body for half a step only (its first half
  // kick), while the fluid takes their whole impulse: the total starts off by F₀ Δt/2.
  BodyForces start;
  start.reset(1);
  coupling(s, start);
  nve.restore_forces(start);
  const Vec3 offset = -0.5 * kUnits.md_time_step * start.force[0];
  for (int step = 0; step < 200; ++step) {
    coupling.set_noise_step(static_cast<std::uint64_t>(s.step) + 1);
    nve.step(s);
    ++s.step;
  }
  // The integrator's forces are those of the last evaluation, half of whose impulse the body has
  // yet to take (the next half kick): count it.
  const Vec3 pending = 0.5 * kUnits.md_time_step * nve.forces().force[0];
  std::printf("body momentum %.4e -> %.4e; total drift %.2e\n", (mass * Vec3(0.05, -0.02, 0.01)).norm(), (mass * s.particles.velocity(0)).norm(),
              (total() + pending - before - offset).norm());
  EXPECT_GT((mass * s.particles.velocity(0) - mass * Vec3(0.05, -0.02, 0.01)).norm(), 1.0);  // momentum did move between body and fluid
  EXPECT_LT((total() + pending - before - offset).norm(), 1e-10 * mass);
}

TEST(BodyFluidCoupling, AFixedRaspberryTakesTheMomentumOfTheDrivingForce) {
  const Vec3 semi = Vec3::Constant(2.25);
  const RaspberryGeometry g = make_raspberry(semi);
  const int edge = 12;
  LbFluid fluid({edge, edge, edge}, LbParameters{kRho, kNu * kUnits.lb_time_step(), 0.0, 0.0, 0.0, 5});
  const double g_md = 1e-4;  // force density along z, MD units (M0/(σ² t0²))
  fluid.set_body_force(Vec3(0, 0, g_md / kUnits.force_from_lattice()));
  BodyFluidCoupling coupling(fluid, raspberry_sites(g), {Vec3::Ones()}, kXi, 0.0, 9, kUnits);
  BodyInertia fixed{1.0, Vec3::Ones()};
  fixed.fixed = true;
  RigidBodyNve nve(kUnits.md_time_step, {fixed}, [&](const State& st, BodyForces& out) { coupling(st, out); },
                   [&](State& st, double dt) { coupling.after_step(st, dt); });
  State s = one_body(edge, Vec3::Zero(), Vec3::Zero());
  const double drive = g_md * edge * edge * edge;  // total force on the fluid, MD units
  // The mean flow relaxes against the raspberry's drag in about 2300 MD steps: run thirteen.
  // The two MD steps of an LB step see different fluid velocities (the second one half the
  // first one's impulse), so their forces differ: the momentum balance holds for their mean.
  Vec3 drag = Vec3::Zero();
  for (int step = 0; step < 30000; ++step) {
    coupling.set_noise_step(static_cast<std::uint64_t>(s.step) + 1);
    nve.step(s);
    ++s.step;
    if (step >= 30000 - 2) drag += 0.5 * nve.forces().force[0];
  }
  const double mean_u = coupling.fluid_momentum().z() / (kRho * edge * edge * edge);
  std::printf("drag on the fixed raspberry %.6e (drive %.6e), mean fluid velocity %.4e: drag / (6 pi eta u) = %.3f nm\n", drag.z(), drive, mean_u,
              drag.z() / (6 * M_PI * kRho * kNu * mean_u));
  EXPECT_NEAR(drag.z(), drive, 1e-4 * drive);
  EXPECT_NEAR(drag.x(), 0.0, 1e-4 * drive);  // no drive across: no steady force across
  EXPECT_NEAR(drag.y(), 0.0, 1e-4 * drive);
}

// BdIntegrator (bd/bd_integrator.hpp), the Itô updates of spec 20 §3:
// - the noise basis is orthonormal and right-handed about û;
// - one step's first moments: the drift of a constant force split by D_∥ and D_⊥ along and across
//   û, the turn of û by a constant torque, D_r T × û Δt/kT, plus the −2D_rΔt û of the
//   renormalisation (10⁵ rods, one step, against 4 standard errors);
// - caps clip the systematic force and torque by norm and are counted;
// - results are the same bits with 1 and 2 threads, and a fresh integrator on a copy of the state
//   continues bit for bit (the noise is keyed by step and particle);
// - bad settings are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "anisodyn/bd/bd_integrator.hpp"
#include "anisodyn/bd/external_torque.hpp"
#include "anisodyn/bd/slender_body.hpp"
#include "anisodyn/core/quaternion.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/core/statistics.hpp"
#include "thread_count.hpp"

using namespace anisodyn;

namespace {
Species rod_species() { return Species{"rod", Shape::spherocylinder(5.0, 0.1), 1.0, {}, {}}; }

/// n rods with random centres in a box of edge 100, axes along x or random.
State rods(std::size_t n, bool random_orientations, std::uint64_t seed = 1) {
  const Quat along_x(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitY()));  // body z onto lab x
  State s;
  s.species = {rod_species()};
  s.box = Box(Vec3::Constant(100.0));
  Rng rng(seed, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 r(rng.uniform(0, 100), rng.uniform(0, 100), rng.uniform(0, 100));
    const Quat q = random_orientations ? uniform_quaternion(rng.uniform(), rng.uniform(), rng.uniform()) : along_x;
    s.particles.add(0, r, q, static_cast<std::int64_t>(i));
  }
  return s;
}

BdSettings settings(double dt) {
  BdSettings b;
  b.time_step = dt;
  b.kT = 1.0;
  b.seed = 7;
  b.diffusion = {BdDiffusion{2.0, 1.0, 0.5}};
  return b;
}

ForceField constant(const Vec3& f, const Vec3& t) {
  return [f, t](const State& s, BodyForces& out) {
    for (std::size_t i = 0; i < s.particles.size(); ++i) {
      out.force[i] += f;
      out.torque[i] += t;
    }
  };
}

void advance(BdIntegrator& bd, State& s, int steps) {
  for (int k = 0; k < steps; ++k) {
    s.time += bd.step(s);
    ++s.step;
  }
}

}  // namespace

TEST(BdIntegrator, NoiseBasisIsOrthonormalAndRightHanded) {
  Rng rng(3, 3);
  for (int k = 0; k < 1000; ++k) {
    const Vec3 u = uniform_quaternion(rng.uniform(), rng.uniform(), rng.uniform()) * Vec3::UnitZ();
    Vec3 e1, e2;
    perpendicular_basis(u, e1, e2);
    EXPECT_NEAR(e1.norm(), 1.0, 1e-14);
    EXPECT_NEAR(e2.norm(), 1.0, 1e-14);
    EXPECT_NEAR(e1.dot(u), 0.0, 1e-14);
    EXPECT_NEAR(e2.dot(u), 0.0, 1e-14);
    EXPECT_NEAR(e1.cross(e2).dot(u), 1.0, 1e-14);
  }
}

TEST(BdIntegrator, OneStepDriftFollowsTheAnisotropicMobilityAndTheTorque) {
  // Rods along x; force with parts along and across û; torque along z turns û towards +y.
  const double dt = 1e-4;
  const Vec3 force(30.0, 40.0, 0.0), torque(0.0, 0.0, 20.0);  // rods along x
  State s = rods(100000, false);
  const State start = s;
  BdIntegrator bd(settings(dt), constant(force, torque));
  advance(bd, s, 1);
  std::vector<double> dx, dy, dz, du_x, du_y;
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    const Vec3 d = s.box.min_image(s.particles.position(i) - start.particles.position(i));
    dx.push_back(d.x());
    dy.push_back(d.y());
    dz.push_back(d.z());
    const Vec3 u = s.particles.orientation(i) * Vec3::UnitZ();
    du_x.push_back(u.x() - 1.0);
    du_y.push_back(u.y());
  }
  const BdDiffusion d = settings(dt).diffusion[0];
  // û' = (û + a ŷ + ξ)/|…| with a = D_r T dt/kT and |ξ|² of mean 4 D_r dt: E[û'_x] − 1 = E[(1 + x)^(−1/2)] − 1
  // with x = |a ŷ + ξ|², that is −(a² + 4 D_r dt)/2 + 12 (D_r dt)² to second order.
  const double a = d.rotation * torque.z() * dt;
  struct Check { const char* what; std::vector<double>* x; double expected; };
  const Check checks[] = {
      {"x drift: D_par F_x dt", &dx, d.parallel * force.x() * dt},
      {"y drift: D_perp F_y dt", &dy, d.perpendicular * force.y() * dt},
      {"z drift: none", &dz, 0.0},
      // Itô: the renormalisation shortens û by 2 D_r dt on average (the drift of the unit sphere).
      {"u_x: -2 D_r dt", &du_x, -(a * a + 4.0 * d.rotation * dt) / 2.0 + 12.0 * d.rotation * d.rotation * dt * dt},
      {"u_y: D_r (T x u)_y dt", &du_y, a},
  };
  for (const auto& c : checks) {
    const MeanError e = mean_of_independent(*c.x);
    const double m = e.mean, se = e.error;
    EXPECT_LT(std::abs(m - c.expected), 4.0 * se) << c.what << ": " << m << " ± " << se << ", expected " << c.expected;
  }
  // The signal is resolved, so the checks above can fail: drift ≫ standard error.
  EXPECT_GT(std::abs(d.parallel * force.x() * dt), 10.0 * mean_of_independent(dx).error);
  EXPECT_GT(std::abs(d.rotation * torque.z() * dt), 10.0 * mean_of_independent(du_y).error);
}

TEST(BdIntegrator, CapsClipTheSystematicForceAndTorqueByNormAndCountThem) {
  const double dt = 1e-4;
  BdSettings b = settings(dt);
  b.force_cap = 5.0;
  b.torque_cap = 1e6;
  State s = rods(20000, false);
  const State start = s;
  BdIntegrator bd(b, constant(Vec3(300.0, 400.0, 0.0), Vec3(0.0, 0.0, 1.0)));
  advance(bd, s, 1);
  EXPECT_EQ(bd.capped_forces(), 20000);
  EXPECT_EQ(bd.capped_torques(), 0);
  EXPECT_DOUBLE_EQ(bd.systematic().force[0].x(), 300.0);  // before the cap
  std::vector<double> dx;
  for (std::size_t i = 0; i < s.particles.size(); ++i)
    dx.push_back(s.box.min_image(s.particles.position(i) - start.particles.position(i)).x());
  const MeanError e = mean_of_independent(dx);
  const double m = e.mean, se = e.error;
  const double expected = b.diffusion[0].parallel * 3.0 * dt;  // capped force (3, 4, 0)
  EXPECT_LT(std::abs(m - expected), 4.0 * se) << m << " vs " << expected;
}

TEST(BdIntegrator, SameBitsForAnyThreadCountAndFromACopyOfTheState) {
  const auto run = [](int threads, int steps) {
    return testing_support::with_threads(threads, [&] {
      State s = rods(3000, true);
      BdIntegrator bd(settings(1e-3), constant(Vec3(1, 2, 3), Vec3(0.5, 0, 1)));
      advance(bd, s, steps);
      return s;
    });
  };
  const State one = run(1, 20), two = run(2, 20);
  EXPECT_EQ(one.particles.x, two.particles.x);
  EXPECT_EQ(one.particles.qw, two.particles.qw);
  EXPECT_EQ(one.particles.ix, two.particles.ix);
  // Restart: 12 steps, then a fresh integrator on a copy continues to the same bits as 20 steps.
  State half = run(2, 12);
  BdIntegrator fresh(settings(1e-3), constant(Vec3(1, 2, 3), Vec3(0.5, 0, 1)));
  advance(fresh, half, 8);
  EXPECT_EQ(half.particles.x, two.particles.x);
  EXPECT_EQ(half.particles.qz, two.particles.qz);
  EXPECT_EQ(half.step, 20);
}

TEST(BdIntegrator, RefusesBadSettings) {
  BdSettings b = settings(0.0);
  EXPECT_THROW(BdIntegrator(b, nullptr), std::invalid_argument);
  b = settings(1e-3);
  b.kT = -1.0;
  EXPECT_THROW(BdIntegrator(b, nullptr), std::invalid_argument);
  b = settings(1e-3);
  b.diffusion[0].perpendicular = -1.0;
  EXPECT_THROW(BdIntegrator(b, nullptr), std::invalid_argument);
}

TEST(BdSlenderBody, FreeRodDiffusionOfSpec20) {
  // L = 0.88 µm, D = 14.8 nm, η = 10⁻³ Pa s, T = 300 K (70-theory §5.1): D_∥ = 3.0603e-12 m²/s,
  // D_⊥ = 1.5302e-12 m²/s, D_r = 23.711 s⁻¹ (the printed digits).
  const double kT = 1.380649e-23 * 300.0;
  const BdDiffusion d = slender_body_diffusion(0.88e-6, 14.8e-9, 1e-3, kT);
  EXPECT_NEAR(d.parallel, 3.0603e-12, 0.00005e-12);
  EXPECT_NEAR(d.perpendicular, 1.5302e-12, 0.00005e-12);
  EXPECT_NEAR(d.rotation, 23.711, 0.0005);
  EXPECT_NEAR((d.parallel + 2 * d.perpendicular) / 3, 2.0402e-12, 0.00005e-12);  // D_t
  EXPECT_THROW(slender_body_diffusion(1.0, 1.0, 1e-3, kT), std::invalid_argument);
}

TEST(BdExternalTorque, ConfinedRodsTurnAtDrTOverKT) {
  // Method II's free-rod check (spec 20 §6.2): rods in the xy plane, T_ex = 10 kT along z, κ_c = 100 kT.
  // The azimuth φ of û drifts at D_r T/kT (the tangential speed D_r T sinθ/kT over sinθ); no
  // drift without the torque. 1000 rods, 5000 steps of D_r Δt = 10⁻⁴: φ moves 5 rad, SE ≈ 0.03; the
  // azimuth is unwrapped every 10 steps (it moves about 0.05 rad in 10 steps).
  const double dt = 2e-4, T = 10.0;
  BdSettings b = settings(dt);
  State s = rods(1000, false);
  ExternalTorque ext;
  for (std::size_t i = 0; i < s.particles.size(); ++i) ext.particles.push_back(i);
  ext.torque = Vec3(0, 0, T);
  ext.confinement = 100.0;
  BdIntegrator bd(b, [&ext](const State& st, BodyForces& out) { add_external_torque(ext, st, out); });
  std::vector<double> phi_prev(s.particles.size(), 0.0), turned(s.particles.size(), 0.0);  // rods start along x: φ = 0
  const int steps = 5000;
  for (int k = 0; k < steps; ++k) {
    s.time += bd.step(s);
    ++s.step;
    if (s.step % 10 != 0) continue;
    for (std::size_t i = 0; i < s.particles.size(); ++i) {
      const Vec3 u = s.particles.orientation(i) * Vec3::UnitZ();
      const double phi = std::atan2(u.y(), u.x());
      turned[i] += std::remainder(phi - phi_prev[i], 2.0 * M_PI);  // unwrapped
      phi_prev[i] = phi;
    }
  }
  const MeanError w = mean_of_independent(turned);
  const double expected = b.diffusion[0].rotation * T * steps * dt;
  std::printf("azimuth turned: %.4f ± %.4f rad, D_r T t / kT = %.4f\n", w.mean, w.error, expected);
  EXPECT_LT(std::abs(w.mean - expected), 4.0 * w.error) << w.mean << " ± " << w.error << " rad, expected " << expected;
  EXPECT_LT(w.error, 0.02 * expected);
  // The confinement keeps the axes near the plane: ⟨(û·ẑ)²⟩ ≈ kT/κ_c = 0.01.
  double c2 = 0.0;
  for (std::size_t i = 0; i < s.particles.size(); ++i) c2 += std::pow((s.particles.orientation(i) * Vec3::UnitZ()).z(), 2);
  EXPECT_NEAR(c2 / static_cast<double>(s.particles.size()), 0.01, 0.002);
}

// Site–liquid forces of spec 30 §4 (interactions/site_liquid.hpp): the core against the spec's
// table and against central differences of its energy, for every diameter the same shape; the
// friction against its closed form; Newton's third law; the shell noise's variance (fluctuation–
// dissipation: 2 kT ξ/Δt per component), its direction in along_v; thread-count independence; and
// a liquid particle bouncing off a fixed site in NVE, whose energy is kept.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "anisodyn/core/rng.hpp"
#include "anisodyn/interactions/site_liquid.hpp"
#include "thread_count.hpp"

using namespace anisodyn;

namespace {

struct Liquid {
  std::vector<double> x, y, z, vx, vy, vz;
  std::vector<std::int64_t> id;
  LiquidView view() const { return {x.data(), y.data(), z.data(), vx.data(), vy.data(), vz.data(), id.data(), x.size()}; }
};

/// n liquid particles uniform in the box, normal velocities.
Liquid random_liquid(std::size_t n, double edge, std::uint64_t seed) {
  Rng rng(seed, 0);
  Liquid l;
  for (std::size_t i = 0; i < n; ++i) {
    l.x.push_back(rng.uniform(0, edge));
    l.y.push_back(rng.uniform(0, edge));
    l.z.push_back(rng.uniform(0, edge));
    l.vx.push_back(rng.normal());
    l.vy.push_back(rng.normal());
    l.vz.push_back(rng.normal());
    l.id.push_back(static_cast<std::int64_t>(3 * i + 1));
  }
  return l;
}

}  // namespace

TEST(SiteLiquid, CoreMatchesTheSpecTableForEveryDiameter) {
  // spec 30 §4.1, x = r − Δ: U and F to the printed digits.
  const ShiftedMieCore core;
  const double table[4][3] = {{0.98, 8.390, 746.5}, {0.99, 3.224, 334.7}, {1.00, 1.000, 134.6}, {1.01, 0.182, 41.3}};
  for (double d : {1.0, 2.0, 6.0}) {
    for (const auto& row : table) {
      const double r = row[0] + 0.5 * d - 1.0;
      EXPECT_NEAR(core.energy(r, d), row[1], 5e-4) << "d " << d << " x " << row[0];
      EXPECT_NEAR(core.force(r, d), row[2], 0.05 + 1e-4 * row[2]) << "d " << d << " x " << row[0];
    }
    EXPECT_NEAR(core.cutoff(d), 0.5 * d + 0.020408, 1e-6);
    EXPECT_EQ(core.energy(core.cutoff(d) + 1e-9, d), 0.0);
    EXPECT_NEAR(core.energy(core.cutoff(d) - 1e-9, d), 0.0, 1e-12);  // continuous at the cut
  }
  EXPECT_NEAR(core.core.prefactor(), 134.5527, 1e-4);
}

TEST(SiteLiquid, CoreForceIsMinusTheGradientOfTheEnergy) {
  const ShiftedMieCore core;
  Rng rng(3, 0);
  for (int k = 0; k < 1000; ++k) {
    const double d = rng.uniform(1.0, 6.0), r = 0.5 * d + rng.uniform(-0.03, 0.02), h = 1e-7;
    const double fd = -(core.energy(r + h, d) - core.energy(r - h, d)) / (2 * h);
    EXPECT_NEAR(core.force(r, d), fd, 1e-6 * std::abs(fd) + 1e-5) << "d " << d << " r " << r;
  }
}

TEST(SiteLiquid, FrictionAndCoreForcesAndNewtonsThirdLaw) {
  // kT = 0: no noise; each liquid particle gets core + friction, checked against an independent sum.
  SiteLiquidParameters p;
  p.gamma_surface = 10.0 / 3.0;
  p.kT = 0.0;
  SiteLiquidForces forces(p, 0.005, 7);
  const Box box(Vec3::Constant(8.0));
  const Liquid liquid = random_liquid(1536, 8.0, 5);
  const std::vector<SiteView> sites = {{Vec3(4.0, 4.0, 4.0), Vec3(0.3, -0.2, 0.1), 2.0, 0},
                                       {Vec3(4.0, 4.0, 4.5), Vec3(0.3, -0.2, 0.4), 2.0, 1},
                                       {Vec3(0.2, 7.9, 4.0), Vec3(0.0, 0.0, 0.0), 3.0, 2}};  // across the boundary
  std::vector<double> f(3 * liquid.x.size(), 0.0);
  std::vector<Vec3> fs(sites.size(), Vec3::Zero()), ts(sites.size(), Vec3::Zero());
  forces.add(box, sites, liquid.view(), f.data(), fs, ts);
  Vec3 total = Vec3::Zero();
  int in_shell = 0;
  for (std::size_t i = 0; i < liquid.x.size(); ++i) {
    Vec3 expect = Vec3::Zero();
    for (const SiteView& s : sites) {
      const Vec3 rij = box.min_image(Vec3(liquid.x[i], liquid.y[i], liquid.z[i]) - s.position);
      const double r = rij.norm(), outer = 0.5 * s.diameter + 0.5;
      if (r < outer) {
        ++in_shell;
        expect -= p.gamma_surface * (outer - r) / 0.5 * (Vec3(liquid.vx[i], liquid.vy[i], liquid.vz[i]) - s.velocity);
      }
      const double x = r - (0.5 * s.diameter - 1.0);
      const double prefactor = 50.0 * std::pow(50.0 / 49.0, 49.0);  // 134.5527: the bare minimum is −1
      if (x < 50.0 / 49.0) expect += prefactor * (50 * std::pow(x, -51) - 49 * std::pow(x, -50)) * rij / r;
    }
    const Vec3 got(f[3 * i], f[3 * i + 1], f[3 * i + 2]);
    EXPECT_LT((got - expect).norm(), 1e-9 * (1.0 + expect.norm())) << i;
    total += got;
  }
  ASSERT_GT(in_shell, 100);
  for (const Vec3& v : fs) total += v;
  EXPECT_LT(total.norm(), 1e-9);  // Newton's third law: the sites take the opposite
}

TEST(SiteLiquid, SurfaceVelocityFrictionAndItsTorque) {
  // kT = 0. With surface_velocity the friction sees v_i − v_s − ω × (d/2) r̂ and the site takes the
  // torque (d/2) r̂ × (−F) about its centre; the published (centre) model ignores ω and gives no
  // torque. Checked against the closed form for liquid particles in the shell of a spinning site.
  const Box box(Vec3::Constant(10.0));
  const SiteView site{Vec3(5.0, 5.0, 5.0), Vec3(0.1, 0.0, -0.2), 3.0, 4, Vec3(0.4, -1.1, 0.7)};
  // Particles where the core reaches are left out: its huge central forces would swamp the
  // torque's round-off.
  const Liquid all = random_liquid(3000, 10.0, 12);
  Liquid liquid;
  for (std::size_t i = 0; i < all.x.size(); ++i) {
    if ((Vec3(all.x[i], all.y[i], all.z[i]) - site.position).norm() < ShiftedMieCore().cutoff(3.0)) continue;
    liquid.x.push_back(all.x[i]), liquid.y.push_back(all.y[i]), liquid.z.push_back(all.z[i]);
    liquid.vx.push_back(all.vx[i]), liquid.vy.push_back(all.vy[i]), liquid.vz.push_back(all.vz[i]), liquid.id.push_back(all.id[i]);
  }
  for (bool surface : {false, true}) {
    SiteLiquidParameters p;
    p.gamma_surface = 5.0;
    p.kT = 0.0;
    p.surface_velocity = surface;
    SiteLiquidForces forces(p, 0.005, 7);
    std::vector<double> f(3 * liquid.x.size(), 0.0);
    std::vector<Vec3> fs(1, Vec3::Zero()), ts(1, Vec3::Zero());
    forces.add(box, std::vector<SiteView>{site}, liquid.view(), f.data(), fs, ts);
    Vec3 torque = Vec3::Zero();
    int in_shell = 0;
    for (std::size_t i = 0; i < liquid.x.size(); ++i) {
      const Vec3 rij = box.min_image(Vec3(liquid.x[i], liquid.y[i], liquid.z[i]) - site.position);
      const double r = rij.norm(), outer = 1.5 + 0.5;
      if (r >= outer) continue;
      const Vec3 arm = 1.5 * rij / r;
      const Vec3 got(f[3 * i], f[3 * i + 1], f[3 * i + 2]);
      torque += arm.cross(-got);
      ++in_shell;
      const Vec3 v_surface = site.velocity + (surface ? Vec3(site.angular_velocity.cross(arm)) : Vec3::Zero());
      const Vec3 expect = -p.gamma_surface * (outer - r) / 0.5 * (Vec3(liquid.vx[i], liquid.vy[i], liquid.vz[i]) - v_surface);
      ASSERT_LT((got - expect).norm(), 1e-12 * (1.0 + expect.norm())) << i;
    }
    ASSERT_GT(in_shell, 40);  // about 56 in the shell beyond the core
    if (surface) {
      EXPECT_LT((ts[0] - torque).norm(), 1e-9 * torque.norm());
      // The friction drags the spinning site back: the torque opposes ω.
      EXPECT_LT(ts[0].dot(site.angular_velocity), 0.0);
    } else {
      EXPECT_EQ(ts[0], Vec3::Zero());
    }
  }
}

TEST(SiteLiquid, ShellNoiseHasTheFluctuationDissipationVariance) {
  // One liquid particle held in the shell of a site over many noise steps: each component of the
  // noise has variance 2 kT ξ/Δt (vector3d); along_v keeps it along v_is with the same variance.
  for (auto mode : {SiteLiquidParameters::ShellNoise::Vector3d, SiteLiquidParameters::ShellNoise::AlongV}) {
    SiteLiquidParameters p;
    p.gamma_surface = 20.0 / 3.0;
    p.noise = mode;
    SiteLiquidForces forces(p, 0.005, 11);
    const Box box(Vec3::Constant(10.0));
    Liquid l;
    l.x = {5.0 + 1.2}, l.y = {5.0}, l.z = {5.0}, l.vx = {0.0}, l.vy = {0.0}, l.vz = {0.0}, l.id = {42};  // r = 1.2, outside the core
    const std::vector<SiteView> site = {{Vec3(5.0, 5.0, 5.0), Vec3(0.0, 1e-3, 0.0), 2.0, 9}};
    const double xi = forces.friction(1.2, 2.0), target = 2.0 * xi / 0.005;
    const double friction_y = -xi * (-1e-3);
    const int n = 40000;
    Vec3 sum = Vec3::Zero(), sum2 = Vec3::Zero();
    for (int step = 0; step < n; ++step) {
      forces.set_noise_step(static_cast<std::uint64_t>(step));
      std::vector<double> f(3, 0.0);
      std::vector<Vec3> fs(1, Vec3::Zero()), ts(1, Vec3::Zero());
      forces.add(box, site, l.view(), f.data(), fs, ts);
      const Vec3 noise(f[0], f[1] - friction_y, f[2]);
      sum += noise;
      sum2 += noise.cwiseProduct(noise);
      if (mode == SiteLiquidParameters::ShellNoise::AlongV) {
        ASSERT_NEAR(noise.x(), 0.0, 1e-12);  // v_is is along y
      }
    }
    const Vec3 var = sum2 / n - (sum / n).cwiseProduct(sum / n);
    const double se = target * std::sqrt(2.0 / n);  // of a Gaussian variance estimate
    if (mode == SiteLiquidParameters::ShellNoise::Vector3d) {
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(var[k], target, 4 * se) << k;
    } else {
      EXPECT_NEAR(var.y(), target, 4 * se);
    }
  }
}

TEST(SiteLiquid, TheThreadCountDoesNotChangeABit) {
  SiteLiquidParameters p;
  p.gamma_surface = 10.0 / 3.0;
  const Box box(Vec3::Constant(12.0));
  const Liquid liquid = random_liquid(5184, 12.0, 8);
  std::vector<SiteView> sites;
  for (int k = 0; k < 7; ++k) sites.push_back({Vec3(6.0, 6.0, 4.5 + 0.5 * k), Vec3(0.1, 0.0, -0.1), 1.0, static_cast<std::uint64_t>(k)});
  std::vector<std::vector<double>> f;
  std::vector<std::vector<Vec3>> fs;
  for (int threads : {1, 2, 3}) {
    const testing_support::ScopedThreadCount count(threads);
    SiteLiquidForces forces(p, 0.005, 3);
    forces.set_noise_step(17);
    f.emplace_back(3 * liquid.x.size(), 0.0);
    fs.emplace_back(sites.size(), Vec3::Zero());
    std::vector<Vec3> ts(sites.size(), Vec3::Zero());
    forces.add(box, sites, liquid.view(), f.back().data(), fs.back(), ts);
  }
  for (std::size_t t = 1; t < f.size(); ++t) {
    EXPECT_EQ(f[t], f[0]);
    for (std::size_t s = 0; s < sites.size(); ++s) EXPECT_TRUE(fs[t][s] == fs[0][s]);
  }
}

TEST(SiteLiquid, ALiquidParticleBouncingOffAFixedSiteKeepsItsEnergy) {
  // spec 30 §4.1's unit test: NVE, core only, Δt = 0.005; a head-on approach at v = 3 (far above
  // thermal), velocity Verlet, the energy before and after the bounce and its largest excursion.
  SiteLiquidParameters p;
  p.kT = 0.0;
  SiteLiquidForces forces(p, 0.005, 1);
  const Box box(Vec3::Constant(20.0));
  const std::vector<SiteView> site = {{Vec3(10.0, 10.0, 10.0), Vec3::Zero(), 2.0, 0}};
  Liquid l;
  l.x = {12.0}, l.y = {10.0}, l.z = {10.0}, l.vx = {-3.0}, l.vy = {0.0}, l.vz = {0.0}, l.id = {1};
  auto force = [&] {
    std::vector<double> f(3, 0.0);
    std::vector<Vec3> fs(1, Vec3::Zero()), ts(1, Vec3::Zero());
    forces.add(box, site, l.view(), f.data(), fs, ts);
    return f[0];
  };
  auto energy = [&] { return 0.5 * l.vx[0] * l.vx[0] + forces.core().energy(std::abs(l.x[0] - 10.0), 2.0); };
  const double dt = 0.005, e0 = energy();
  double f = force(), worst = 0.0;
  for (int step = 0; step < 400; ++step) {
    l.vx[0] += 0.5 * dt * f;
    l.x[0] += dt * l.vx[0];
    f = force();
    l.vx[0] += 0.5 * dt * f;
    worst = std::max(worst, std::abs(energy() - e0));
  }
  EXPECT_GT(l.vx[0], 0.0);  // bounced
  std::printf("bounce at v = 3, dt = 0.005: energy before %.6f, after %.6f, largest excursion %.2e\n", e0, energy(), worst);
  EXPECT_NEAR(energy(), e0, 1e-3 * e0);
  EXPECT_LT(worst, 0.05 * e0);
}

#include "anisodyn/lb/fluid_checks.hpp"

#include <cmath>

#include "anisodyn/core/statistics.hpp"

namespace anisodyn::lb::checks {

namespace {

constexpr double kHasimoto = 2.837297;

}  // namespace

double shear_wave_viscosity(double nu, int length, int t0, int t1) {
  LbFluid fluid({1, 1, length}, LbParameters{1.0, nu, 0.0, 0.0, 0.0, 1});
  const double k = 2.0 * M_PI / length, amplitude = 1e-4;
  for (int z = 0; z < length; ++z) fluid.set_equilibrium(fluid.node(0, 0, z), 1.0, Vec3(amplitude * std::sin(k * (z + 0.5)), 0, 0));
  double st = 0, sl = 0, stt = 0, stl = 0, count = 0;
  for (int t = 0; t <= t1; ++t) {
    if (t >= t0) {
      double a = 0.0;
      for (int z = 0; z < length; ++z) a += fluid.velocity(fluid.node(0, 0, z)).x() * std::sin(k * (z + 0.5));
      const double l = std::log(2.0 * a / length);
      st += t, sl += l, stt += double(t) * t, stl += t * l, ++count;
    }
    fluid.step();
  }
  const double slope = (count * stl - st * sl) / (count * stt - st * st);
  return -slope / (k * k);
}

std::vector<double> channel_profile(int h, double nu, double bottom, double top, double g) {
  LbFluid fluid({1, h + 2, 1}, LbParameters{1.0, nu, 0.0, 0.0, 0.0, 1});
  fluid.set_solid(fluid.node(0, 0, 0), Vec3(0, 0, bottom));
  fluid.set_solid(fluid.node(0, h + 1, 0), Vec3(0, 0, top));
  fluid.set_body_force(Vec3(0, 0, g));
  const int steps = static_cast<int>(20.0 * h * h / nu);
  for (int s = 0; s < steps; ++s) fluid.step();
  std::vector<double> u;
  for (int y = 1; y <= h; ++y) u.push_back(fluid.velocity(fluid.node(0, y, 0)).z());
  return u;
}

ModeVariances thermal_mode_variances(const LbParameters& p, int edge, int warmup_steps, int blocks, int steps_per_block, int every) {
  LbFluid fluid({edge, edge, edge}, p);
  const double n = static_cast<double>(fluid.nodes());
  for (int s = 0; s < warmup_steps; ++s) fluid.step();
  constexpr int kU = kQ;  // the last entry: ⟨u²⟩ per component
  std::vector<std::vector<double>> block(static_cast<std::size_t>(blocks), std::vector<double>(kQ + 1, 0.0));
  ModeVariances out;
  out.blocks = blocks;
  for (auto& row : block) {
    int samples = 0;
    for (int s = 0; s < steps_per_block; ++s) {
      fluid.step();
      if (s % every != 0) continue;
      ++samples;
      for (std::size_t node = 0; node < fluid.nodes(); ++node) {
        const auto m = fluid.modes(node);
        for (int k = 0; k < kQ; ++k) {
          const double d = k == 0 ? m[0] - p.density : m[static_cast<std::size_t>(k)];
          row[static_cast<std::size_t>(k)] += d * d / n;
        }
        // u = j/ρ from the modes already in hand (no forces act on this fluid).
        row[kU] += Vec3(m[1], m[2], m[3]).squaredNorm() / (m[0] * m[0] * 3.0 * n);
      }
    }
    for (double& v : row) v /= samples;
    out.samples += samples;
  }
  const double mu = p.kT / kCs2;
  for (int k = 0; k <= kQ; ++k) {
    std::vector<double> values;
    for (const auto& row : block) values.push_back(row[static_cast<std::size_t>(k)]);
    const MeanError blocks_mean = mean_of_independent(values);
    const double mean = blocks_mean.mean, se = blocks_mean.error;
    const double conserved = k < kFirstStressMode || k == kU ? 1.0 - 1.0 / n : 1.0;
    const double target = (k == kU ? p.kT / p.density : mu * p.density * kB[k]) * conserved;
    out.ratio.push_back(mean / target);
    out.standard_error.push_back(se / target);
  }
  return out;
}

CoupledBeads coupled_bead_run(const LbParameters& p, int edge, std::size_t beads, double mass, double xi, int warmup_steps, int blocks,
                              int steps_per_block) {
  LbFluid fluid({edge, edge, edge}, p);
  const double h = 0.5;
  const PointCoupling coupling(xi, h, p.kT, p.seed + 1);
  std::vector<Vec3> r, v(beads, Vec3::Zero()), force;
  std::vector<std::uint32_t> id;
  for (std::size_t b = 0; b < beads; ++b) {  // spread through the box, off the nodes
    const double t = static_cast<double>(b);
    r.emplace_back(std::fmod(0.5 + 0.37 * t * edge / 8.0, edge), std::fmod(1.3 + 0.91 * t * edge / 8.0, edge),
                   std::fmod(edge - 0.3 - 0.45 * t * edge / 8.0 + 4.0 * edge, edge));
    id.push_back(static_cast<std::uint32_t>(b));
  }
  std::uint64_t md = 0;
  const auto bead_momentum = [&] {
    Vec3 sum = Vec3::Zero();
    for (const Vec3& u : v) sum += mass * u;
    return sum;
  };
  auto lb_step = [&] {
    for (int sub = 0; sub < 2; ++sub) {
      coupling.couple(fluid, r, v, id, md++, force);
      for (std::size_t b = 0; b < beads; ++b) {
        v[b] += (h / mass) * force[b];
        r[b] += h * v[b];
      }
    }
    fluid.step();
  };
  CoupledBeads out;
  // Both MD half-kicks of an LB step are in the fluid once it has stepped: totals are compared there.
  const Vec3 fluid0 = fluid.total_momentum(), momentum0 = fluid0 + bead_momentum();
  out.initial_mass = fluid.total_mass();
  for (int s = 0; s < warmup_steps; ++s) lb_step();
  std::vector<double> block(static_cast<std::size_t>(blocks), 0.0);
  for (auto& value : block) {
    for (int s = 0; s < steps_per_block; ++s) {
      lb_step();
      for (const Vec3& u : v) value += mass * u.squaredNorm() / (3.0 * static_cast<double>(beads) * steps_per_block * p.kT);
      const Vec3 fluid_momentum = fluid.total_momentum();  // one pass over the lattice for both changes
      out.momentum_change = std::max(out.momentum_change, (fluid_momentum + bead_momentum() - momentum0).norm());
      out.mass_change = std::max(out.mass_change, std::abs(fluid.total_mass() - out.initial_mass));
      out.fluid_momentum_change = std::max(out.fluid_momentum_change, (fluid_momentum - fluid0).norm());
    }
  }
  const MeanError temperature = mean_of_independent(block);
  out.bead_temperature = temperature.mean, out.bead_temperature_se = temperature.error;
  out.expected_temperature = 1.0 / (1.0 - 0.5 * xi * h / mass);
  return out;
}

double pulled_bead_mobility(int L, double nu, double xi, const Vec3& start, CouplingVelocity convention) {
  const double h = 0.5, mass = 2.0 * xi * h;
  LbFluid fluid({L, L, L}, LbParameters{1.0, nu, 0.0, 0.0, 0.0, 1});
  const PointCoupling coupling(xi, h, 0.0, 1, convention);
  const Vec3 pull(1e-4, 0, 0);
  fluid.set_body_force(-pull / static_cast<double>(fluid.nodes()));
  std::vector<Vec3> r{start}, v{Vec3::Zero()}, force;
  const std::vector<std::uint32_t> id{0};
  const int steps = static_cast<int>(4.0 * L * L / nu);
  double sum = 0.0;
  int samples = 0;
  for (int s = 0; s < steps; ++s) {
    for (int sub = 0; sub < 2; ++sub) {
      coupling.couple(fluid, r, v, id, static_cast<std::uint64_t>(2 * s + sub), force);
      v[0] += (h / mass) * (force[0] + pull);
      r[0] += h * v[0];
    }
    fluid.step();
    if (s >= steps / 2) {
      sum += v[0].x() - fluid.total_momentum().x() / fluid.total_mass();
      ++samples;
    }
  }
  return sum / samples / pull.x();
}

double ahlrichs_dunweg_g(double mobility, double xi, double eta, double L) {
  return 1.0 / (eta * (mobility - 1.0 / xi + kHasimoto / (6.0 * M_PI * eta * L)));
}

}  // namespace anisodyn::lb::checks

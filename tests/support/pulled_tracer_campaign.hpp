#pragma once
// Runner-level pulled-tracer campaigns for the statistical tests: a tracer sphere in a bath of
// spheres, equilibrated by MC, then DMC replicas through DmcRunner (preliminary balance, tracer as
// the reference species, the bath as the clock) written to H5MD and analysed by the active
// microrheology stage, exactly as anisodyn-dmc and anisodyn-microrheology would.
//
// Also the independent reference for an ideal bath of points: in equilibrium the N_b points are
// independent and uniform over the box outside the tracer (free volume V_f), so a tracer trial
// displaced by Δ passes the overlap test with probability (1 − V(|Δ|)/V_f)^N_b, V the part of the
// displaced exclusion sphere outside the current one; the expectations of one trial over the
// uniform proposal box then give A_0, A_t and the drift that the DMC mapping turns into a velocity.
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/analysis/active_microrheology.hpp"
#include "anisodyn/analysis/trajectory.hpp"
#include "anisodyn/dmc/dmc_protocol.hpp"
#include "anisodyn/dmc/dmc_runner.hpp"
#include "anisodyn/io/h5md.hpp"
#include "anisodyn/tool/json_config.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/mc/mc_engine.hpp"

namespace anisodyn::testing_support {

/// Stokes–Einstein D of a sphere of diameter d in the DMC units (k_BT = μ = 1).
inline double stokes_einstein(double d) { return 1.0 / (3.0 * std::numbers::pi * d); }

struct BathSystem {
  double box = 3.0;                 // cubic edge
  int lattice = 3;                  // hard-sphere bath: lattice sites per edge, site 0 holds the tracer
  int points = 0;                   // point bath: this many points placed at random outside the tracer instead
  double bath_diameter = 1.0;
  double tracer_diameter = 1.0;
  int mc_cycles = 2000;             // NVT equilibration (move sizes tuned to 40%)

  int bath_count() const { return points > 0 ? points : lattice * lattice * lattice - 1; }
  /// The centre distance at which the tracer touches a bath particle.
  double contact() const { return 0.5 * (bath_diameter + tracer_diameter); }
};

/// The tracer and its bath (on a simple cubic lattice, or random points), melted by MC.
inline State tracer_in_bath(const BathSystem& b, std::uint64_t seed) {
  State s;
  s.box = Box(Vec3::Constant(b.box));
  const double Db = stokes_einstein(b.bath_diameter), Dt = stokes_einstein(b.tracer_diameter);
  s.species.push_back(Species{"bath", Shape::sphere(b.bath_diameter), 1.0, Vec3::Constant(Db), Vec3::Zero()});
  s.species.push_back(Species{"tracer", Shape::sphere(b.tracer_diameter), 1.0, Vec3::Constant(Dt), Vec3::Zero()});
  if (b.points > 0) {
    const Vec3 centre = Vec3::Constant(0.5 * b.box);
    s.particles.add(1, centre, Quat::Identity(), 0);
    Rng rng(seed, 1);
    for (std::int64_t id = 1; id <= b.points;) {
      const Vec3 r(rng.uniform(0.0, b.box), rng.uniform(0.0, b.box), rng.uniform(0.0, b.box));
      if (s.box.min_image(r - centre).norm() > 1.01 * b.contact()) s.particles.add(0, r, Quat::Identity(), id++);
    }
  } else {
    const double a = b.box / b.lattice;
    std::int64_t id = 0;
    for (int x = 0; x < b.lattice; ++x)
      for (int y = 0; y < b.lattice; ++y)
        for (int z = 0; z < b.lattice; ++z, ++id) {
          const int species = id == 0 ? 1 : 0;
          s.particles.add(species, Vec3((x + 0.5) * a, (y + 0.5) * a, (z + 0.5) * a), Quat::Identity(), id);
        }
  }
  McEngine mc(s, RngState{seed, 0, 0, 4});
  mc.move_sizes().translate.assign(2, 0.1);
  mc.move_sizes().rotate.assign(2, 0.0);
  MoveCounters last = mc.counters();
  for (int c = 1; c <= b.mc_cycles; ++c) {
    mc.cycle();
    if (c % 100 == 0) {
      mc.tune(0.4, mc.counters().since(last));
      last = mc.counters();
    }
  }
  return s;
}

struct TracerRun {
  double pe = 1.0;
  double tracer_dt = 0.01;
  std::int64_t preliminary_cycles = 5000;
  std::int64_t cycles = 20000;
  std::string a0 = "overlap_pass";  // or "one"
  std::int64_t record_every = 10;
};

/// The anisodyn-dmc configuration of a run (frames at the start and the end only).
inline nlohmann::json tracer_config(const TracerRun& r) {
  return {{"seed", 11},
          {"cycles", r.cycles},
          {"time_step", {{"tracer", r.tracer_dt}}},
          {"balance", {{"mode", "equilibrium"}, {"reference", "tracer"}, {"preliminary_cycles", r.preliminary_cycles}}},
          {"tracer", {{"species", "tracer"}, {"pe", r.pe}, {"axis", "z"}, {"a0", r.a0}, {"record_every", r.record_every}}},
          {"frames", {{"every_cycles", r.cycles}}},
          {"observe_every", 100}};
}

/// Runs replica `replica` from `start` into `path`; returns the run's summary.
inline nlohmann::json run_tracer_replica(const State& start, const TracerRun& r, std::uint64_t replica, const std::string& path) {
  State state = start;
  nlohmann::json config = tracer_config(r);
  tool::ConfigNode cfg(config, "test.json");
  DmcProtocol protocol = parse_dmc_protocol(cfg);
  cfg.finish();
  protocol.replica = replica;
  config["replica"] = replica;
  DmcRunner runner(state, protocol, "test.json", /*quiet=*/true);
  io::H5mdWriter out(path, io::H5mdHeader{"anisodyn", "", "test", config, nlohmann::json::object(), state.species});
  runner.run(out, 0, [] {});
  out.commit();
  return runner.summary();
}

/// γ_eff/γ_0 and the rest of the active analysis over the given replicas.
inline analysis::ActiveResult analyse_tracer(const std::vector<std::string>& paths, double pe, double tracer_diameter) {
  analysis::ActiveMicrorheologySettings s;
  s.species = "tracer";
  s.bath_species = "bath";
  s.beta_force = pe / (0.5 * tracer_diameter);
  s.D_s = stokes_einstein(tracer_diameter);
  s.density_map = false;
  analysis::ActiveMicrorheology a(s, paths.size(), "test.json");
  analysis::TrajectoryNeeds needs;
  needs.positions = true;
  needs.observables = {"tracer_position"};
  analysis::for_each_replica(paths, needs, [&](const analysis::Trajectory& t, std::size_t) { a.accumulate(t); },
                             analysis::kIndependentTimes);
  return a.compute();
}

/// Volume of a sphere of radius R displaced by d that lies outside the undisplaced one.
inline double displaced_sphere_excess(double R, double d) {
  if (d >= 2.0 * R) return 4.0 / 3.0 * std::numbers::pi * R * R * R;
  const double lens = std::numbers::pi * (4.0 * R + d) * (2.0 * R - d) * (2.0 * R - d) / 12.0;
  return 4.0 / 3.0 * std::numbers::pi * R * R * R - lens;
}

/// One tracer trial in an equilibrium bath of `points` ideal points in the free volume `free_volume`
/// (contact radius R): the expected overlap pass A_0, acceptance A_t and displacement along the
/// force, over the DMC proposal (uniform in ±δ_∥ along the force, ±δ_⊥ across it) and the Metropolis
/// factor min(1, e^{βF Δz}).
struct PointBathTrial {
  double a0 = 0, at = 0, drift = 0;
};
inline PointBathTrial point_bath_trial(int points, double free_volume, double R, double beta_force, double d_par, double d_perp,
                                       int nodes = 120) {
  // Midpoint rule on 2n × 2n × 2n cells, the z range split at 0 where the Metropolis factor has a kink.
  PointBathTrial t;
  const double hz = d_par / nodes, hp = d_perp / nodes;
  for (int k = 0; k < 2 * nodes; ++k) {
    const double z = -d_par + (k + 0.5) * hz;
    const double metropolis = std::min(1.0, std::exp(beta_force * z));
    for (int i = 0; i < 2 * nodes; ++i) {
      const double x = -d_perp + (i + 0.5) * hp;
      for (int j = 0; j < 2 * nodes; ++j) {
        const double y = -d_perp + (j + 0.5) * hp;
        const double excess = displaced_sphere_excess(R, std::sqrt(x * x + y * y + z * z));
        const double pass = std::pow(1.0 - excess / free_volume, points);
        t.a0 += pass;
        t.at += pass * metropolis;
        t.drift += pass * metropolis * z;
      }
    }
  }
  const double n = 8.0 * nodes * nodes * nodes;
  t.a0 /= n;
  t.at /= n;
  t.drift /= n;
  return t;
}

}  // namespace anisodyn::testing_support

// anisodyn-lb-checks: the fluid checks of study D1 (spec 60 D1, spec 40 §2.5 and §3) as one stage
// with no input: thermalisation of every mode and of u per node, the shear-wave viscosity, plug
// flow between moving walls, mass and momentum with coupled beads, and a pulled bead's mobility
// against Ahlrichs and Dünweg's effective friction. Each measurement comes from lb/fluid_checks.hpp
// (which the unit and statistical tests assert on) and is written with its reference.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "anisodyn/analysis/analysis_output.hpp"
#include "anisodyn/core/error.hpp"
#include "anisodyn/lb/fluid_checks.hpp"
#include "anisodyn/tool/atomic_file.hpp"
#include "anisodyn/tool/command_line.hpp"
#include "anisodyn/tool/json_config.hpp"
#include "anisodyn/tool/provenance.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;
namespace checks = anisodyn::lb::checks;

namespace {

// Spec 40's fluid in lattice units (spec 70 §7.1): ρ = 6.004, ν = 0.8 σ²/t0 → 0.016, k_BT = 4×10⁻⁴;
// water's ν → 0.113514. The point-coupled beads: ξ_bead = 200 scaled by s (0.56 in lattice units), m = 10.
constexpr double kDensity = 6.004, kNuScaled = 0.016, kNuWater = 0.113514, kKT = 4e-4;
constexpr double kBeadFriction = 0.56, kBeadMass = 10.0;
constexpr double kAhlrichsDunwegG = 25.0;  // spec 70 §7.4 (external)
constexpr double kWallSpeed = 2.7953e-4;    // spec 70 §7.1: 2.20 m/s in lattice units

tool::Description description() {
  tool::Description d;
  d.role = tool::Role::Analysis;
  d.replica = false;
  d.inputs = {"none", 0, 0, "none: each check sets up its own lattice"};
  d.output = {"analysis", "HDF5 + CSV",
              "scalars u2_ratio, worst_mode_pull, shear_wave_nu_ratio_*, plug_flow_deviation, momentum_change, mass_change, "
              "bead_temperature, mobility_over_AD_* and g_*; tables modes, shear_wave, bead_mobility",
              nullptr};
  d.parameters = {
      tool::optional("box", "integer", 24, "edge (nodes) of the thermal lattices and of the channel's width"),
      tool::optional("lb_steps", "integer", 5000, "LB steps of each thermal run after its warm-up (in 10 blocks)"),
      tool::optional("warmup_steps", "integer", 1000, "LB steps before the thermal runs are sampled (spec 40 §2.4)"),
      tool::optional("mobility_positions", "integer", 16, "random bead positions in a cell (fixed seed) for the position-averaged mobility"),
      tool::optional("seed", "integer", 1, "the noise's seed"),
      tool::optional("csv", "boolean", true, "write CSV files beside the HDF5 output"),
  };
  d.cost = tool::negligible_cost("seconds to a minute at the default sizes (docs/lb.md)");
  return d;
}

void progress(bool quiet, const char* what) {
  if (!quiet) std::fprintf(stderr, "anisodyn-lb-checks: %s\n", what);
}

/// Thermal equilibrium of spec 40's fluid: every mode and ⟨u²⟩ against their targets.
void thermal_checks(AnalysisOutput& out, int box, int warmup, int steps, std::uint64_t seed) {
  const lb::LbParameters p{kDensity, kNuScaled, 0.0, 0.0, kKT, seed};
  const int blocks = 10, every = 10;
  const checks::ModeVariances v = checks::thermal_mode_variances(p, box, warmup, blocks, std::max(every, steps / blocks), every);
  std::vector<double> index, ratio, se, pull;
  double worst = 0.0;
  for (int k = 0; k <= lb::kQ; ++k) {
    const auto i = static_cast<std::size_t>(k);
    index.push_back(k);
    ratio.push_back(v.ratio[i]);
    se.push_back(v.standard_error[i]);
    pull.push_back((v.ratio[i] - 1.0) / v.standard_error[i]);
    worst = std::max(worst, std::abs(pull.back()));
  }
  Table& t = out.table("modes", "per mode k (k = 19: <u_a^2> per component) the mean square over nodes over its target");
  t.add("mode", "1", "mode index k of spec 40 §2.2; 19 is the velocity per node and component", index);
  t.add("ratio", "1", "<m_k^2> / (mu rho b_k) (modes 0-3 and u times 1 - 1/N: fixed totals)", ratio);
  t.add("ratio_se", "1", "standard error over 10 blocks", se);
  t.add("pull", "1", "(ratio - 1) / SE", pull);
  // The blocks give honest errors only when each is longer than the slowest relaxation, the longest
  // shear wave's 1/(ν k²) with k = 2π/box: the details say how many of those a block spans.
  const double slowest = box * box / (4.0 * M_PI * M_PI * kNuScaled);
  const nlohmann::json details = {{"box", box}, {"lb_steps", steps}, {"blocks", blocks}, {"sample_every", every}, {"density", kDensity},
                                  {"nu_lattice", kNuScaled}, {"kT_lattice", kKT}, {"slowest_relaxation_steps", slowest},
                                  {"block_over_slowest_relaxation", (steps / blocks) / slowest}};
  const auto u = static_cast<std::size_t>(lb::kQ);
  out.scalar({"u2_ratio", v.ratio[u], v.standard_error[u], "1", "<u_a^2> rho / kT per node and component over (1 - 1/N); target 1", details});
  out.scalar({"worst_mode_pull", worst, 0.0, "1", "the largest |ratio - 1| / SE over the 19 modes and u (about 3 at most for 20 Gaussian pulls; the SE is too small when a block "
                                                       "is shorter than a few slowest relaxations: details)", details});
}

/// ν from shear-wave decay: spec 40's scaled fluid, water's, and τ = 1, on a 64-node wavelength.
void shear_wave_checks(AnalysisOutput& out) {
  const int length = 64;
  const double k = 2.0 * M_PI / length;
  std::vector<double> nus, measured;
  for (const auto& [name, nu] : {std::pair{"scaled", kNuScaled}, std::pair{"water", kNuWater}, std::pair{"tau_1", 1.0 / 6.0}}) {
    const double m = checks::shear_wave_viscosity(nu, length, 20, static_cast<int>(1.0 / (nu * k * k)));
    nus.push_back(nu);
    measured.push_back(m);
    out.scalar({std::string("shear_wave_nu_ratio_") + name, m / nu, 0.0, "1",
                "nu from the decay of a shear wave of 64 nodes over about one e-fold, over the set nu (target 1; spec 40 §2.5: within 1%)",
                {{"nu_lattice", nu}, {"wavelength", length}}});
  }
  Table& t = out.table("shear_wave", "shear-wave viscosity against the set one (lattice units)");
  t.add("nu", "1", "the set kinematic viscosity (lattice units)", nus);
  t.add("nu_measured", "1", "from the decay exp(-nu k^2 t) of the wave's amplitude", measured);
}

/// Plug flow: both walls moving at spec 40's Stokes-flow speed, the fluid between them at rest at first.
void plug_flow_check(AnalysisOutput& out, int box) {
  const int h = box - 2;
  double worst = 0.0;
  for (double u : checks::channel_profile(h, kNuScaled, kWallSpeed, kWallSpeed, 0.0)) worst = std::max(worst, std::abs(u / kWallSpeed - 1.0));
  out.scalar({"plug_flow_deviation", worst, 0.0, "1",
              "largest |u/U - 1| over the channel's nodes after 20 momentum-diffusion times, walls moving together at U (target 0)",
              {{"channel_nodes", h}, {"wall_speed_lattice", kWallSpeed}, {"nu_lattice", kNuScaled}}});
}

/// Beads coupled to the thermal fluid: conservation and the beads' temperature.
void coupled_bead_checks(AnalysisOutput& out, int box, int warmup, int steps, std::uint64_t seed) {
  const lb::LbParameters p{kDensity, kNuScaled, 0.0, 0.0, kKT, seed + 100};
  const int blocks = 10;
  const checks::CoupledBeads c = checks::coupled_bead_run(p, box, 16, kBeadMass, kBeadFriction, warmup, blocks, std::max(1, steps / blocks));
  const nlohmann::json details = {{"box", box}, {"beads", 16}, {"bead_mass", kBeadMass}, {"bead_friction", kBeadFriction},
                                  {"fluid_momentum_change", c.fluid_momentum_change}, {"fluid_mass", c.initial_mass}};
  out.scalar({"momentum_change", c.momentum_change / c.initial_mass, 0.0, "1",
              "largest change of the total momentum (fluid + beads) over the run, over the fluid's mass (target: round-off)", details});
  out.scalar({"mass_change", c.mass_change / c.initial_mass, 0.0, "1", "largest relative change of the fluid's mass (target: round-off)", details});
  out.scalar({"bead_temperature", c.bead_temperature, c.bead_temperature_se, "kT",
              "m<v_a^2> of the free beads; expected 1/(1 - xi h/2m), the explicit kick's own bias",
              {{"expected", c.expected_temperature}, {"box", box}}});
}

/// A pulled bead's mobility against 1/ξ + 1/(25 η) − 2.837/(6πηL), at the node, the cell centre, an
/// off-lattice point and averaged over random points in the cell, for both coupling velocities.
void mobility_checks(AnalysisOutput& out, int positions, std::uint64_t seed) {
  const int L = 12;
  const double nu = 0.5, eta = nu, xi = 1.0;  // ρ = 1
  const double reference = 1.0 / xi + 1.0 / (kAhlrichsDunwegG * eta) - 2.837297 / (6.0 * M_PI * eta * L);
  std::vector<Vec3> points{Vec3(3.5, 3.5, 3.5), Vec3(4.0, 4.0, 4.0), Vec3(3.8, 4.3, 3.6)};
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> cell(3.5, 4.5);
  for (int k = 0; k < positions; ++k) points.emplace_back(cell(rng), cell(rng), cell(rng));
  // The distance to the nearest node centre (where the stencil sits on one node) orders the table.
  const auto node_distance = [](const Vec3& r) {
    Vec3 d;
    for (int a = 0; a < 3; ++a) d[a] = r[a] - (std::floor(r[a]) + 0.5);
    return d.norm();
  };
  std::vector<double> distance, ratio[2], g[2];
  for (const Vec3& r : points) distance.push_back(node_distance(r));
  static const char* where[] = {"node", "centre", "off_lattice"};
  for (int c = 0; c < 2; ++c) {
    const auto convention = c == 0 ? lb::CouplingVelocity::kWithHalfForce : lb::CouplingVelocity::kMomentumOnly;
    const std::string name = c == 0 ? "half_force" : "momentum_only";
    std::vector<double> random_ratio;
    for (std::size_t p = 0; p < points.size(); ++p) {
      const double mu = checks::pulled_bead_mobility(L, nu, xi, points[p], convention);
      ratio[c].push_back(mu / reference);
      g[c].push_back(checks::ahlrichs_dunweg_g(mu, xi, eta, L));
      if (p >= 3) {
        random_ratio.push_back(ratio[c].back());
        continue;
      }
      out.scalar({"mobility_over_AD_" + name + "_" + where[p], ratio[c].back(), 0.0, "1",
                  "pulled bead's mobility over Ahlrichs-Dunweg's 1/xi + 1/(g eta) - 2.837/(6 pi eta L), g = 25 (target 1 within 2%)",
                  {{"position", {points[p].x(), points[p].y(), points[p].z()}}, {"g_measured", g[c].back()}, {"box", L}, {"nu", nu}, {"xi", xi}}});
    }
    double mean = 0.0, var = 0.0;
    for (double r : random_ratio) mean += r / random_ratio.size();
    for (double r : random_ratio) var += (r - mean) * (r - mean) / (random_ratio.size() - 1.0);
    out.scalar({"mobility_over_AD_" + name + "_mean", mean, std::sqrt(var / random_ratio.size()), "1",
                "the same ratio averaged over random positions in a cell (error: their spread / sqrt(n))",
                {{"positions", positions}, {"box", L}, {"nu", nu}, {"xi", xi}}});
  }
  std::vector<std::size_t> order(points.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return distance[a] < distance[b]; });
  const auto sorted = [&](const std::vector<double>& v) {
    std::vector<double> out_v;
    for (std::size_t k : order) out_v.push_back(v[k]);
    return out_v;
  };
  Table& t = out.table("bead_mobility", "pulled bead: mobility over Ahlrichs-Dunweg's (g = 25) and the g it implies, per position, "
                                        "by the distance from the nearest node (the node, the cell centre, an off-lattice point, random points)");
  t.add("node_distance", "1", "distance of the bead from the nearest node centre (lattice units)", sorted(distance));
  t.add("ratio_half_force", "1", "mobility / (1/xi + 1/(25 eta) - 2.837/(6 pi eta L)) with u = (j + f/2)/rho (spec 40)", sorted(ratio[0]));
  t.add("ratio_momentum_only", "1", "the same with u = j/rho (Ahlrichs-Dunweg's)", sorted(ratio[1]));
  t.add("g_half_force", "1", "Ahlrichs-Dunweg g from the mobility, u = (j + f/2)/rho", sorted(g[0]));
  t.add("g_momentum_only", "1", "the same, u = j/rho", sorted(g[1]));
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-lb-checks", "the LB fluid checks of study D1 (spec 40 §2.5, §3)", "See docs/lb.md.", description()};
  return tool::run_tool(argc, argv, info, [&](tool::CommonOptions& opt) {
    if (!opt.inputs.empty()) throw InputError("--input", "", "anisodyn-lb-checks takes no input file (each check sets up its own lattice)");
    if (opt.output.empty()) throw InputError("--output", "", "expected an output file (.h5); CSV files are written beside it");
    tool::ConfigNode cfg(opt.config, opt.config_name());
    const int box = static_cast<int>(cfg.positive_integer("box", 24));
    if (box < 4) cfg.fail("box", "expected at least 4 nodes");
    const int steps = static_cast<int>(cfg.positive_integer("lb_steps", 5000));
    if (steps < 100) cfg.fail("lb_steps", "expected at least 100 steps (10 blocks of at least 10)");
    const int warmup = static_cast<int>(cfg.non_negative_integer("warmup_steps", 1000));
    const int positions = static_cast<int>(cfg.positive_integer("mobility_positions", 16));
    if (positions < 2) cfg.fail("mobility_positions", "expected at least 2 (the mean's error needs two)");
    const auto seed = static_cast<std::uint64_t>(cfg.non_negative_integer("seed", 1));
    const bool csv = cfg.boolean("csv", true);
    cfg.finish();
    tool::check_output_writable(opt.output);
    AnalysisOutput out(opt.output, opt.config, nlohmann::json::object());
    progress(opt.quiet, "thermalisation of every mode");
    thermal_checks(out, box, warmup, steps, seed);
    progress(opt.quiet, "shear-wave viscosity");
    shear_wave_checks(out);
    progress(opt.quiet, "plug flow between moving walls");
    plug_flow_check(out, box);
    progress(opt.quiet, "conservation with coupled beads");
    coupled_bead_checks(out, box, warmup, steps, seed);
    progress(opt.quiet, "single-bead mobility");
    mobility_checks(out, positions, seed);
    out.set_provenance(tool::make_provenance(info.name, opt.argv, {}));
    out.write(csv);
    if (!opt.quiet) std::fprintf(stderr, "anisodyn-lb-checks: wrote %s\n", opt.output.c_str());
  });
}

// anisodyn-lb-checks: the checks of studies D0 and D1 (spec 60) as one stage with no input.
// Suite "fluid" (D1; spec 40 §2.5 and §3): thermalisation of every mode and of u per node, the
// shear-wave viscosity, plug flow between moving walls, mass and momentum with coupled beads, and
// a pulled bead's mobility against Ahlrichs and Dünweg's effective friction (lb/fluid_checks.hpp).
// Suite "analytic" (D0; spec 40 §1, §5, §8–9): the raspberry analysis on synthetic Brownian bodies
// of known D, the pore-frame transform on free motion, the spheroid nearest-point bisection against
// brute force, and the unit conversions against spec 70 §7.1 (analysis/lb_analytic_checks.hpp).
// The unit and statistical tests assert on the same functions; this stage writes each measurement
// with its reference. (D0's spheroid factors A, B, E–L are checked by the report: they are Python.)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "anisodyn/analysis/analysis_output.hpp"
#include "anisodyn/analysis/lb_analytic_checks.hpp"
#include "anisodyn/core/error.hpp"
#include "anisodyn/core/statistics.hpp"
#include "anisodyn/lb/fluid_checks.hpp"
#include "anisodyn/lb/si_units.hpp"
#include "anisodyn/tool/atomic_file.hpp"
#include "anisodyn/tool/command_line.hpp"
#include "anisodyn/tool/json_config.hpp"
#include "anisodyn/tool/provenance.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;
namespace fluid_checks = anisodyn::lb::checks;

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
              "fluid: scalars u2_ratio, worst_mode_pull, shear_wave_nu_ratio_*, plug_flow_deviation, momentum_change, mass_change, "
              "bead_temperature, mobility_over_AD_*; tables modes, shear_wave, bead_mobility. analytic: scalars synthetic_*_ratio, "
              "pore_frame_worst_pull, nearest_point_*, unit_*; tables synthetic_body, pore_frame_free",
              nullptr};
  d.parameters = {
      tool::optional("suite", "string", "fluid", "fluid (study D1) | analytic (study D0)"),
      tool::optional("box", "integer", 24, "fluid: edge (nodes) of the thermal lattices and of the channel's width"),
      tool::optional("lb_steps", "integer", 5000, "fluid: LB steps of each thermal run after its warm-up (in 10 blocks)"),
      tool::optional("warmup_steps", "integer", 1000, "fluid: LB steps before the thermal runs are sampled (spec 40 §2.4)"),
      tool::optional("mobility_positions", "integer", 16, "fluid: random bead positions in a cell (fixed seed) for the position-averaged mobility"),
      tool::optional("bodies", "integer", 300, "analytic: synthetic Brownian bodies per case (independent samples)"),
      tool::optional("intervals", "integer", 1500, "analytic: frame intervals per synthetic body"),
      tool::optional("seed", "integer", 1, "the seed of the noise (fluid) or of the synthetic motion (analytic)"),
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
  const fluid_checks::ModeVariances v = fluid_checks::thermal_mode_variances(p, box, warmup, blocks, std::max(every, steps / blocks), every);
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
  // The targets are the linearised theory's. u = j/ρ with a fluctuating ρ adds, at second order,
  // 3<δρ²>/ρ0² = 9 k_BT/ρ0 (c_s² = 1/3): 6×10⁻⁴ here, which long runs resolve.
  nlohmann::json u_details = details;
  u_details["second_order_expectation"] = 1.0 + 9.0 * kKT / kDensity;
  out.scalar({"u2_ratio", v.ratio[u], v.standard_error[u], "1",
              "<u_a^2> rho / kT per node and component over (1 - 1/N); target 1 (second order in kT/rho: 1 + 9 kT/rho, details)", u_details});
  out.scalar({"worst_mode_pull", worst, 0.0, "1", "the largest |ratio - 1| / SE over the 19 modes and u (about 3 at most for 20 Gaussian pulls; the SE is too small when a block "
                                                       "is shorter than a few slowest relaxations: details)", details});
}

/// ν from shear-wave decay: spec 40's scaled fluid, water's, and τ = 1, on a 64-node wavelength.
void shear_wave_checks(AnalysisOutput& out) {
  const int length = 64;
  const double k = 2.0 * M_PI / length;
  std::vector<double> nus, measured;
  for (const auto& [name, nu] : {std::pair{"scaled", kNuScaled}, std::pair{"water", kNuWater}, std::pair{"tau_1", 1.0 / 6.0}}) {
    const double m = fluid_checks::shear_wave_viscosity(nu, length, 20, static_cast<int>(1.0 / (nu * k * k)));
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
  for (double u : fluid_checks::channel_profile(h, kNuScaled, kWallSpeed, kWallSpeed, 0.0)) worst = std::max(worst, std::abs(u / kWallSpeed - 1.0));
  out.scalar({"plug_flow_deviation", worst, 0.0, "1",
              "largest |u/U - 1| over the channel's nodes after 20 momentum-diffusion times, walls moving together at U (target 0)",
              {{"channel_nodes", h}, {"wall_speed_lattice", kWallSpeed}, {"nu_lattice", kNuScaled}}});
}

/// Beads coupled to the thermal fluid: conservation and the beads' temperature.
void coupled_bead_checks(AnalysisOutput& out, int box, int warmup, int steps, std::uint64_t seed) {
  const lb::LbParameters p{kDensity, kNuScaled, 0.0, 0.0, kKT, seed + 100};
  const int blocks = 10;
  const fluid_checks::CoupledBeads c = fluid_checks::coupled_bead_run(p, box, 16, kBeadMass, kBeadFriction, warmup, blocks, std::max(1, steps / blocks));
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
      const double mu = fluid_checks::pulled_bead_mobility(L, nu, xi, points[p], convention);
      ratio[c].push_back(mu / reference);
      g[c].push_back(fluid_checks::ahlrichs_dunweg_g(mu, xi, eta, L));
      if (p >= 3) {
        random_ratio.push_back(ratio[c].back());
        continue;
      }
      out.scalar({"mobility_over_AD_" + name + "_" + where[p], ratio[c].back(), 0.0, "1",
                  "pulled bead's mobility over Ahlrichs-Dunweg's 1/xi + 1/(g eta) - 2.837/(6 pi eta L), g = 25 (target 1 within 2%)",
                  {{"position", {points[p].x(), points[p].y(), points[p].z()}}, {"g_measured", g[c].back()}, {"box", L}, {"nu", nu}, {"xi", xi}}});
    }
    const MeanError mean = mean_of_independent(random_ratio);
    out.scalar({"mobility_over_AD_" + name + "_mean", mean.mean, mean.error, "1",
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

// --- suite "analytic" (D0) ---------------------------------------------------------------------

void add_recovered(AnalysisOutput& out, std::vector<double> (&cols)[4], const std::string& name, const analysis::checks::Recovered& r,
                   const std::string& definition, const nlohmann::json& details) {
  out.scalar({"synthetic_" + name + "_ratio", r.value / r.expected, r.error / r.expected, "1", definition + " over its expected value (target 1)",
              details});
  cols[0].push_back(static_cast<double>(cols[0].size()));
  cols[1].push_back(r.value), cols[2].push_back(r.error), cols[3].push_back(r.expected);
}

/// Synthetic Brownian bodies of known body-frame D through the lag curves of anisodyn-lb-diffusion:
/// a spheroid-like body (D_∥ ≠ D_⊥) and a sphere (the single-vector estimator's 4 D_r τ).
void synthetic_body_checks(AnalysisOutput& out, int bodies, int intervals, std::uint64_t seed) {
  const Vec3 dt(0.02, 0.05, 0.05), dr(4e-4, 1e-3, 1e-3);
  const double alpha = 0.9;
  const auto b = analysis::checks::synthetic_body(dt, dr, alpha, bodies, intervals, seed);
  const auto sphere = analysis::checks::synthetic_body(Vec3::Constant(0.03), Vec3::Constant(8e-4), alpha, bodies, intervals, seed + 1);
  const nlohmann::json details = {{"bodies", bodies}, {"intervals", intervals}, {"D_t_body", {dt.x(), dt.y(), dt.z()}},
                                  {"D_r_body", {dr.x(), dr.y(), dr.z()}}, {"alpha", alpha}, {"lag", 1}};
  std::vector<double> cols[4];
  Table& t = out.table("synthetic_body", "lag-1 mean squares of synthetic Brownian bodies (rows in the order of the synthetic_* scalars)");
  add_recovered(out, cols, "lab_msd", b.lab_msd, "lab MSD at one lag, 2 sum D_t,i", details);
  add_recovered(out, cols, "single_vector", b.reference_angle, "reference-vector angle^2, 2[D_r,par sin^2 a + D_r,perp (1 + cos^2 a)] (spec 40 §8.2)", details);
  add_recovered(out, cols, "three_axis", b.three_axis, "three-axis angle^2, 12 mean D_r", details);
  static const char* axis[] = {"x", "y", "z"};
  for (std::size_t i = 0; i < 3; ++i) {
    add_recovered(out, cols, std::string("body_msd_") + axis[i], b.body_msd[i], std::string("body-frame MSD along body ") + axis[i] + ", 2 D_t,i (§8.3)", details);
    add_recovered(out, cols, std::string("body_angle_") + axis[i], b.body_angle[i],
                  std::string("projected angle^2 about body ") + axis[i] + ", 2 D_r,i (§8.4, the projection method)", details);
  }
  nlohmann::json sphere_details = details;
  sphere_details["D_t_body"] = {0.03, 0.03, 0.03};
  sphere_details["D_r_body"] = {8e-4, 8e-4, 8e-4};
  add_recovered(out, cols, "sphere_single_vector", sphere.reference_angle, "a sphere's reference-vector angle^2, 4 D_r (the 4 tau estimator)", sphere_details);
  t.add("row", "1", "row number", cols[0]);
  t.add("measured", "1", "mean over the bodies", cols[1]);
  t.add("measured_se", "1", "standard error over the bodies", cols[2]);
  t.add("expected", "1", "from the D given to the synthetic motion", cols[3]);
  // The paper's conventions divide by 6 tau (lab) and 3 tau (body axes) instead of 4 tau and 2 tau.
  out.scalar({"synthetic_paper_convention_ratio", sphere.reference_angle.value / 6.0 / 8e-4, sphere.reference_angle.error / 6.0 / 8e-4, "1",
              "the sphere's angle^2 / (6 tau) over its D_r: the paper convention's 2/3 (spec 40 §8.2)", sphere_details});
  out.scalar({"synthetic_paper_convention_body_ratio", b.body_angle[0].value / 3.0 / dr.x(), b.body_angle[0].error / 3.0 / dr.x(), "1",
              "the body-x angle^2 / (3 tau) over D_r,x: the paper convention's 2/3 (spec 40 §8.4)", details});
}

/// The pore-frame transform on free Brownian motion started in a disk about the axis.
void pore_frame_checks(AnalysisOutput& out, std::uint64_t seed) {
  const double D = 0.01, gap = 5.0;
  const auto f = analysis::checks::pore_frame_free_motion(D, gap, 400, 500, seed);
  Table& t = out.table("pore_frame_free", "free Brownian motion through the pore-frame analysis: S_i = 2D / <dx_i^2> per beta bin (target 1)");
  t.add("beta", "1", "bin centre of d/(R_pore - R)", f.beta);
  t.add("count", "1", "one-lag samples in the bin", f.count);
  static const char* axis[] = {"x", "y", "z"};
  for (std::size_t i = 0; i < 3; ++i) {
    std::vector<double> S, se;
    for (std::size_t b = 0; b < f.beta.size(); ++b) S.push_back(1.0 / f.ratio[i][b]), se.push_back(f.error[i][b] / (f.ratio[i][b] * f.ratio[i][b]));
    t.add(std::string("S_") + axis[i], "1", std::string("2D over the mean square along pore ") + axis[i] + " (x radial, y azimuthal, z axial)", S);
    t.add(std::string("S_") + axis[i] + "_se", "1", "standard error", se);
  }
  const nlohmann::json details = {{"D", D}, {"gap", gap}, {"runs", 400}, {"steps", 500}, {"bins_checked", f.bins_checked}};
  out.scalar({"pore_frame_worst_pull", f.worst_pull, 0.0, "1",
              "largest |S_i - 1| / SE over the pore axes of the bins from beta = 0.2 with >= 2000 samples (Gaussian: about 3 at most)", details});
}

/// The spheroid nearest-point bisection against a brute-force search, inside and outside three bodies.
void nearest_point_checks(AnalysisOutput& out) {
  const Vec3 axes[3] = {Vec3(1.687, 6.746, 6.746), Vec3(10.709, 2.677, 2.677), Vec3(3.0, 2.0, 1.5)};  // spec 70 §7.3's φ = 1/4 and 4
  const Vec3 points[5] = {Vec3(1.2, -0.7, 0.4), Vec3(5.0, 3.0, -2.0), Vec3(-0.3, 0.2, 2.9), Vec3(0.1, 4.4, 0.2), Vec3(9.0, -0.5, 0.3)};
  double worst = 0.0, off = 0.0;
  for (const Vec3& a : axes)
    for (const Vec3& r : points) {
      const auto n = analysis::checks::nearest_point_against_brute_force(a, r);
      worst = std::max(worst, std::abs(n.bisection - n.brute_force)), off = std::max(off, n.off_surface);
    }
  const nlohmann::json details = {{"bodies", 3}, {"points", 5}, {"grid", "1000 x 2000 (theta, phi), refined to 1e-9 rad"}};
  out.scalar({"nearest_point_max_difference", worst, 0.0, "nm", "largest |bisection distance - brute-force distance| (target: the grid's resolution, < 1e-7)", details});
  out.scalar({"nearest_point_max_off_surface", off, 0.0, "1", "largest |sum (p_i/s_i)^2 - 1| of the bisection's points (target: round-off)", details});
}

/// Spec 40 §1's reduced units in SI against spec 70 §7.1's printed values.
void unit_checks(AnalysisOutput& out) {
  using U = lb::SiUnits;
  const double rho_water = 6.00407, eta_water = rho_water * U::kWaterViscosity;
  const lb::ViscosityScaling scaled;
  struct Row {
    const char* name;
    double value, printed;
    const char* what;
  };
  const Row rows[] = {{"t0_ps", U::time() * 1e12, 6.35294, "t0 in ps"},
                      {"friction_kg_per_s", U::friction(), 2.61381e-14, "the friction unit M0/t0 in kg/s"},
                      {"eta_water", eta_water, 34.0774, "water's eta = rho nu in M0/(sigma t0)"},
                      {"eta_water_Pa_s", eta_water * U::dynamic_viscosity(), 8.9072e-4, "water's eta in Pa s"},
                      {"friction_scale", scaled.friction_scale(), 0.140951, "s = 0.8/5.6757"},
                      {"six_pi_eta_water_SI", 6 * M_PI * eta_water * U::dynamic_viscosity(), 1.67897e-2, "6 pi eta_water in kg/(m s)"},
                      {"wall_speed", 2.20 / U::velocity(), 0.0139765, "2.20 m/s in sigma/t0"},
                      {"recording_ps", 200 * 0.01 * U::time() * 1e12, 12.7059, "200 MD steps of 0.01 t0 in ps"}};
  for (const Row& r : rows)
    out.scalar({std::string("unit_") + r.name, r.value / r.printed - 1.0, 0.0, "1",
                std::string(r.what) + ": relative difference from spec 70 §7.1's printed value (its last digit: about 1e-5)",
                {{"value", r.value}, {"spec70", r.printed}}});
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-lb-checks", "the LB checks of studies D0 (analytic) and D1 (fluid)", "See docs/lb.md.", description()};
  return tool::run_tool(argc, argv, info, [&](tool::CommonOptions& opt) {
    if (!opt.inputs.empty()) throw InputError("--input", "", "anisodyn-lb-checks takes no input file (each check sets up its own lattice)");
    if (opt.output.empty()) throw InputError("--output", "", "expected an output file (.h5); CSV files are written beside it");
    tool::ConfigNode cfg(opt.config, opt.config_name());
    const bool fluid = cfg.choice("suite", {"fluid", "analytic"}, "fluid") == "fluid";
    for (const char* key : {"box", "lb_steps", "warmup_steps", "mobility_positions"}) cfg.reject_unless(fluid, key, "in the analytic suite");
    for (const char* key : {"bodies", "intervals"}) cfg.reject_unless(!fluid, key, "in the fluid suite");
    const int box = fluid ? static_cast<int>(cfg.positive_integer("box", 24)) : 0;
    if (fluid && box < 4) cfg.fail("box", "expected at least 4 nodes");
    const int steps = fluid ? static_cast<int>(cfg.positive_integer("lb_steps", 5000)) : 0;
    if (fluid && steps < 100) cfg.fail("lb_steps", "expected at least 100 steps (10 blocks of at least 10)");
    const int warmup = fluid ? static_cast<int>(cfg.non_negative_integer("warmup_steps", 1000)) : 0;
    const int positions = fluid ? static_cast<int>(cfg.positive_integer("mobility_positions", 16)) : 0;
    if (fluid && positions < 2) cfg.fail("mobility_positions", "expected at least 2 (the mean's error needs two)");
    const int bodies = fluid ? 0 : static_cast<int>(cfg.positive_integer("bodies", 300));
    if (!fluid && bodies < 10) cfg.fail("bodies", "expected at least 10 (the errors come from the spread over bodies)");
    const int intervals = fluid ? 0 : static_cast<int>(cfg.positive_integer("intervals", 1500));
    const auto seed = static_cast<std::uint64_t>(cfg.non_negative_integer("seed", 1));
    const bool csv = cfg.boolean("csv", true);
    cfg.finish();
    tool::check_output_writable(opt.output);
    AnalysisOutput out(opt.output, opt.config, nlohmann::json::object());
    if (fluid) {
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
    } else {
      progress(opt.quiet, "synthetic Brownian bodies");
      synthetic_body_checks(out, bodies, intervals, seed);
      progress(opt.quiet, "pore frame of free motion");
      pore_frame_checks(out, seed + 2);
      progress(opt.quiet, "nearest surface points");
      nearest_point_checks(out);
      unit_checks(out);
    }
    out.set_provenance(tool::make_provenance(info.name, opt.argv, {}));
    out.write(csv);
    if (!opt.quiet) std::fprintf(stderr, "anisodyn-lb-checks: wrote %s\n", opt.output.c_str());
  });
}

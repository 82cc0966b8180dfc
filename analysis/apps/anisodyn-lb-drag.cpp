// anisodyn-lb-drag: the translational friction of a raspberry held fixed in the plug flow between
// moving walls (spec 40 §7.2, study D2a), or in the flow a body force drives through a periodic box
// (Hasimoto's periodic array): ξ^t_col = F·û / U from anisodyn-lb's colloid_force over the window's
// rows (the flow steady), with û the walls' velocity or the body force's direction and U the walls'
// speed or the fluid's mean velocity along û (its momentum over its mass, row by row); in the run's
// units, in water units (÷ the friction scale s of spec 40 §1.1) and in SI, and as ξ/(6πηR) and
// the effective radius ξ/(6πη) (η = ρν of the simulated fluid with the simulated friction, or of
// water with the water-unit friction: the same ratio).
#include <cmath>

#include "anisodyn/analysis/observable_summary.hpp"
#include "anisodyn/core/error.hpp"
#include "anisodyn/analysis/stage.hpp"
#include "anisodyn/io/h5md.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

tool::Description description() {
  return analysis_description(
      {tool::optional("blocks", "integer", 10, "a single run's rows in this many blocks for the errors (several runs: one sample each)")},
      "scalars xi_t (simulated units), xi_t_water, xi_t_SI, mobility_t, R_eff_t, xi_t_over_6pi_eta_R, U (the wall speed), each with its error");
}

struct DragRun {
  Vec3 direction = Vec3::Zero();
  double speed = 0.0;        ///< the walls' speed; 0 for a body-force drive (U from the fluid's momentum)
  double fluid_mass = 0.0;   ///< ρ V, for the mean velocity of a body-force drive
  double density = 0.0, viscosity = 0.0, friction_scale = 1.0, friction_si = 0.0;
  double radius = 0.0;  ///< sphere: R; spheroid: the equal-volume sphere's (a b c)^{1/3}
};

Vec3 vec3_of(const std::vector<double>& v) { return Vec3(v.at(0), v.at(1), v.at(2)); }

/// What a run's parameters say about its flow, fluid and body; InputError naming the file unless
/// it is an anisodyn-lb run of one fixed raspberry between moving walls or in a driven periodic box.
DragRun read_run(const std::string& path) {
  const io::H5mdReader reader(path);
  const nlohmann::json config = reader.parameters();
  const nlohmann::json provenance = reader.provenance();
  if (!provenance.contains("units") || !config.contains("raspberries"))
    throw InputError(path, "/parameters", "an anisodyn-lb run (its parameters have no raspberries or units)");
  const nlohmann::json& units = provenance.at("units");
  if (!config["raspberries"].value("fixed", false))
    throw InputError(path, "/parameters/config", "a run of raspberries held fixed (raspberries.fixed true): a free body's force is no drag");
  if (config.contains("pore")) throw InputError(path, "/parameters/config", "walls or a body force, not a pore");
  const std::vector<double> zero{0, 0, 0};
  const Vec3 wall = vec3_of(config.contains("walls") ? config["walls"].value("velocity", zero) : zero);
  const Vec3 drive = vec3_of(config.contains("fluid") ? config["fluid"].value("body_force", zero) : zero);
  DragRun d;
  d.density = units.at("simulated_dynamic_viscosity").get<double>() / units.at("simulated_kinematic_viscosity").get<double>();
  d.viscosity = units.at("simulated_kinematic_viscosity").get<double>();
  d.friction_scale = units.at("friction_scale").get<double>();
  d.friction_si = units.at("friction_kg_per_s").get<double>();
  const State first = reader.read_frame(0);
  if ((wall.norm() > 0.0) == (drive.norm() > 0.0))
    throw InputError(path, "/parameters/config", "either moving walls (walls.velocity) or a body force (fluid.body_force) driving the flow");
  d.speed = wall.norm();
  d.direction = wall.norm() > 0.0 ? Vec3(wall / wall.norm()) : Vec3(drive / drive.norm());
  d.fluid_mass = d.density * first.box.volume();
  if (first.particles.size() != 1) throw InputError(path, "/particles/all", "one raspberry (the drag is the force on the only body)");
  const Shape& shape = first.species.at(static_cast<std::size_t>(first.particles.species[0])).shape;
  d.radius = shape.kind == ShapeKind::Sphere ? 0.5 * shape.diameter : std::cbrt(shape.half_extents().prod());
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-lb-drag", "Stokes-flow friction of a fixed raspberry (spec 40 §7.2)", "See docs/lb.md.", description()};
  return run_analysis_stage(argc, argv, info, [](StageRun& run) {
    const auto blocks = static_cast<std::size_t>(run.cfg.positive_integer("blocks", 10));
    run.cfg.reject_unless(run.inputs.size() == 1, "blocks", "with several runs (each run is one sample)");
    if (run.inputs.size() == 1 && blocks < 2) run.fail("blocks", "expected at least 2 blocks for an error bar");
    run.cfg.finish();
    std::vector<DragRun> runs;
    std::vector<ObservableRows> forces;
    std::vector<double> speeds;
    for (std::size_t k = 0; k < run.inputs.size(); ++k) {
      run.report_replica(k, run.inputs[k]);
      runs.push_back(read_run(run.inputs[k]));
      const DragRun& d = runs.back();
      const auto keep = [&](double t) { return run.window.contains(t); };
      const ObservableRows rows = read_rows(run.inputs[k], "colloid_force", keep);
      const ObservableRows momentum = d.speed > 0.0 ? ObservableRows{} : read_rows(run.inputs[k], "fluid_momentum", keep);
      // Per row: the friction F·û / U, and U.
      ObservableRows along{rows.time, {}, 1, "M0/t0"};
      for (std::size_t r = 0; r < rows.time.size(); ++r) {
        const double u = d.speed > 0.0 ? d.speed : d.direction.dot(vec3_of({momentum.value[3 * r], momentum.value[3 * r + 1], momentum.value[3 * r + 2]})) / d.fluid_mass;
        along.value.push_back(d.direction.dot(Vec3(rows.value[3 * r], rows.value[3 * r + 1], rows.value[3 * r + 2])) / u);
        speeds.push_back(u);
      }
      if (run.inputs.size() == 1 && along.time.size() < blocks)
        run.fail("blocks", "expected at least as many rows of colloid_force in the window (" + std::to_string(along.time.size()) + ") as blocks");
      if (k > 0 && (std::abs(d.speed - runs[0].speed) > 1e-12 * runs[0].speed || std::abs(d.viscosity - runs[0].viscosity) > 1e-12 ||
                    std::abs(d.friction_scale - runs[0].friction_scale) > 1e-12 || std::abs(d.radius - runs[0].radius) > 1e-12))
        throw InputError(run.inputs[k], "/parameters", "the same flow, fluid and body as " + run.inputs[0] + " (replicas of one system)");
      forces.push_back(std::move(along));
    }
    const DragRun& d = runs.front();
    const Estimate friction = observable_means(forces, blocks).front();
    const double xi = friction.value, xi_error = friction.error;
    double mean_speed = 0.0;
    for (const double u : speeds) mean_speed += u / static_cast<double>(speeds.size());
    const double six_pi_eta = 6.0 * M_PI * d.density * d.viscosity;
    const nlohmann::json details = {{"samples", run.inputs.size() == 1 ? blocks : run.inputs.size()},
                                    {"error", run.inputs.size() == 1 ? "jackknife over blocks of the rows" : "over runs"},
                                    {"radius", d.radius}, {"friction_scale", d.friction_scale}};
    run.out.scalar({"U", mean_speed, 0.0, "sigma/t0", "the walls' speed (the plug flow's far-field velocity), or the driven fluid's mean velocity along the drive, mean over the rows", details});
    run.out.scalar({"xi_t", xi, xi_error, "M0/t0", "drag along the flow over U, mean over the rows: the translational friction in the run's units (simulated viscosity)", details});
    run.out.scalar({"xi_t_water", xi / d.friction_scale, xi_error / d.friction_scale, "M0/t0",
                    "xi_t in water units: divided by the friction scale s = nu_sim/nu_water of nominal bead frictions (spec 40 §1.1; 1 otherwise)", details});
    run.out.scalar({"xi_t_SI", xi / d.friction_scale * d.friction_si, xi_error / d.friction_scale * d.friction_si, "kg/s", "xi_t_water in SI", details});
    run.out.scalar({"mobility_t", 1.0 / xi, xi_error / (xi * xi), "t0/M0",
                    "U over the drag: 1/xi_t, which Hasimoto's periodic correction makes linear in 1/L (spec 40 §8.1: its intercept is 1/xi_0)", details});
    run.out.scalar({"R_eff_t", xi / six_pi_eta, xi_error / six_pi_eta, "sigma", "effective hydrodynamic radius xi_t / (6 pi eta), eta = rho nu of the simulated fluid",
                    details});
    run.out.scalar({"xi_t_over_6pi_eta_R", xi / (six_pi_eta * d.radius), xi_error / (six_pi_eta * d.radius), "1",
                    "xi_t / (6 pi eta R), R the design radius (spheroids: (a b c)^(1/3)); 1 for a Stokes sphere in an unbounded fluid", details});
  });
}

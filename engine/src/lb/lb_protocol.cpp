#include "anisodyn/lb/lb_protocol.hpp"

#include <cmath>

namespace anisodyn::lb {

namespace {

LbProtocol::Fluid parse_fluid(tool::ConfigNode& f) {
  LbProtocol::Fluid fluid;
  fluid.agrid = f.positive("agrid", fluid.agrid);
  fluid.lb_steps = static_cast<int>(f.positive_integer("lb_steps", fluid.lb_steps));
  fluid.density = f.positive("density", fluid.density);
  fluid.viscosity = f.number("viscosity", fluid.viscosity);
  if (!(fluid.viscosity > 0.0))
    f.fail("viscosity", "expected a positive kinematic viscosity: the relaxation time tau = 3 nu dt_LB / a^2 + 1/2 must exceed 1/2");
  const auto relaxation = [&f](const char* key) {
    const double g = f.number(key, 0.0);
    if (!(g > -1.0 && g <= 1.0)) f.fail(key, "expected a relaxation factor gamma in (-1, 1] (0: relaxed fully every step)");
    return g;
  };
  fluid.bulk_relaxation = relaxation("bulk_relaxation");
  fluid.ghost_relaxation = relaxation("ghost_relaxation");
  fluid.thermal = f.boolean("thermal", fluid.thermal);
  fluid.initial_velocity = f.vec3("initial_velocity", fluid.initial_velocity);
  fluid.warmup_steps = f.non_negative_integer("warmup_steps", fluid.warmup_steps);
  fluid.body_force = f.vec3("body_force", fluid.body_force);
  if (fluid.warmup_steps % fluid.lb_steps != 0)
    f.fail("warmup_steps", "expected a whole number of LB steps: a multiple of lb_steps (" + std::to_string(fluid.lb_steps) + ")");
  return fluid;
}

LbProtocol::Raspberries parse_raspberries(tool::ConfigNode& r, const LbProtocol::Fluid& fluid) {
  LbProtocol::Raspberries rasp;
  if (r.has("species")) {
    rasp.species = r.strings("species");
    if (rasp.species.empty()) r.fail("species", "expected at least one raspberry species (leave the key out for every species)");
  }
  rasp.xi_bead = r.positive("xi_bead");
  rasp.scaling.xi_bead_is_nominal = r.boolean("xi_bead_is_nominal", true);
  rasp.scaling.simulated_viscosity = fluid.viscosity;
  rasp.centre_couples = r.boolean("centre_couples", true);
  rasp.fixed = r.boolean("fixed", false);
  rasp.velocity = r.choice("coupling_velocity", {"with_half_force", "momentum_only"}, "with_half_force") == "with_half_force"
                      ? CouplingVelocity::kWithHalfForce
                      : CouplingVelocity::kMomentumOnly;
  r.reject_unless(!rasp.fixed, "allow_unstable", "with fixed raspberries (a body held in place has no dynamics to become unstable)");
  rasp.allow_unstable = r.boolean("allow_unstable", false);
  rasp.outer_layer = r.choice("layers", {"two", "single"}, "two") == "two";
  return rasp;
}

}  // namespace

LbProtocol parse_lb_protocol(tool::ConfigNode& cfg) {
  LbProtocol p;
  static_cast<run::TimeStepRun&>(p) = run::parse_time_step_run(cfg, "LB");
  if (auto f = cfg.optional_object("fluid")) p.fluid = parse_fluid(*f);
  cfg.reject_unless(p.fluid.thermal, "kT", "with fluid.thermal false (the deterministic fluid and beads have no temperature)");
  p.kT = cfg.positive("kT", p.kT);
  auto r = cfg.object("raspberries");
  p.raspberries = parse_raspberries(r, p.fluid);
  if (auto w = cfg.optional_object("walls")) {
    LbProtocol::Walls walls;
    const std::string normal = w->choice("normal", {"x", "y", "z"});
    walls.normal = normal[0] - 'x';
    walls.velocity = w->vec3("velocity", walls.velocity);
    if (walls.velocity[walls.normal] != 0.0)
      w->fail("velocity", "expected a tangential velocity: its " + normal + " component (along the wall's normal) must be 0");
    p.walls = walls;
  }
  if (auto q = cfg.optional_object("pore")) {
    if (p.walls) q->fail("", "expected either walls or a pore, not both");
    PoreParameters pore;
    pore.radius = q->positive("radius");
    pore.wall_bead_radius = q->positive("wall_bead_radius", pore.wall_bead_radius);
    pore.bead_spacing = q->positive("wall_bead_spacing", pore.bead_spacing);
    pore.epsilon = q->positive("epsilon", pore.epsilon);
    p.pore = pore;
  }
  return p;
}

}  // namespace anisodyn::lb

#include "anisodyn/dpd/dpd_protocol.hpp"

namespace anisodyn {

DpdProtocol parse_dpd_protocol(tool::ConfigNode& cfg) {
  DpdProtocol p;
  static_cast<run::TimeStepRun&>(p) = run::parse_time_step_run(cfg, "DPD");
  p.liquid.kT = cfg.positive("kT", 1.0);
  auto liquid = cfg.object("liquid");
  if (liquid.has("species")) {
    p.liquid_species = liquid.strings("species");
    if (p.liquid_species.empty()) liquid.fail("species", "expected at least one liquid species");
  }
  p.liquid.a = liquid.non_negative("a", p.liquid.a);
  p.liquid.gamma = liquid.non_negative("gamma", p.liquid.gamma);
  p.liquid.cutoff = liquid.positive("cutoff", p.liquid.cutoff);
  p.skin = liquid.positive("skin", p.skin);
  if (cfg.has("velocities"))
    p.velocities = cfg.choice("velocities", {"input", "maxwell_boltzmann"}) == "input" ? DpdProtocol::Velocities::Input
                                                                                      : DpdProtocol::Velocities::MaxwellBoltzmann;
  p.green_kubo = run::parse_green_kubo(cfg);
  if (auto c = cfg.optional_object("colloids")) {
    DpdProtocol::Colloids col;
    col.species = c->strings("species");
    if (col.species.empty()) c->fail("species", "expected at least one colloid species");
    col.shell.gamma_surface = c->non_negative("gamma_surface", 0.0);
    col.shell.shell = c->positive("shell", 0.5);
    col.shell.noise = c->choice("shell_noise", {"vector3d", "along_v"}, "vector3d") == "vector3d"
                          ? SiteLiquidParameters::ShellNoise::Vector3d
                          : SiteLiquidParameters::ShellNoise::AlongV;
    c->reject_unless(col.shell.gamma_surface > 0.0, "shell", "with gamma_surface 0 (there is no friction shell)");
    c->reject_unless(col.shell.gamma_surface > 0.0, "shell_noise", "with gamma_surface 0 (there is no friction shell, hence no noise)");
    col.shell.kT = p.liquid.kT;
    col.mass_density = c->positive("mass_density", col.mass_density);
    col.site_spacing = c->positive("site_spacing", col.site_spacing);
    col.fixed = c->boolean("fixed", false);
    col.shell.surface_velocity = c->choice("friction_velocity", {"centre", "surface"}, "centre") == "surface";
    c->reject_unless(col.shell.gamma_surface > 0.0, "friction_velocity", "with gamma_surface 0 (there is no friction shell)");
    if (col.shell.surface_velocity && col.fixed)
      c->fail("friction_velocity", "expected \"centre\" for fixed colloids (a body held in place has no surface motion)");
    p.colloids = col;
  }
  if (auto w = cfg.optional_object("walls")) {
    w->choice("type", {"flat_mie"});  // the only kind (spec 30 §6); required, so that a new kind is a new name
    FlatWallParameters walls;
    walls.height = w->positive("height");
    const auto gammas = w->numbers("gamma_surface");
    if (gammas.size() != 2 || gammas[0] < 0 || gammas[1] < 0)
      w->fail("gamma_surface", "expected [bottom, top], two non-negative surface frictions");
    walls.gamma_surface = {gammas[0], gammas[1]};
    const bool friction = gammas[0] > 0 || gammas[1] > 0;
    walls.shell = w->positive("shell", walls.shell);
    walls.noise = w->choice("shell_noise", {"vector3d", "along_v"}, "vector3d") == "vector3d" ? SiteLiquidParameters::ShellNoise::Vector3d
                                                                                             : SiteLiquidParameters::ShellNoise::AlongV;
    w->reject_unless(friction, "shell", "with gamma_surface [0, 0] (there is no friction shell)");
    w->reject_unless(friction, "shell_noise", "with gamma_surface [0, 0] (there is no friction shell, hence no noise)");
    walls.kT = p.liquid.kT;
    p.walls = walls;
  }
  if (cfg.has("drive")) {
    // One slab as an object, or several as a list of them.
    const auto parse_drive = [](tool::ConfigNode& d) {
      DpdProtocol::Drive drive;
      drive.force = d.vec3("force");
      drive.z_min = d.number("z_min", drive.z_min);
      drive.z_max = d.number("z_max", drive.z_max);
      if (!(drive.z_min < drive.z_max)) d.fail("z_max", "expected z_max above z_min");
      return drive;
    };
    if (cfg.raw().at("drive").is_array())
      for (tool::ConfigNode& d : cfg.objects("drive")) p.drives.push_back(parse_drive(d));
    else {
      tool::ConfigNode d = cfg.object("drive");
      p.drives.push_back(parse_drive(d));
    }
  }
  if (auto pr = cfg.optional_object("profiles")) {
    DpdProtocol::Profiles prof;
    if (pr->has("z_bin")) prof.z_bin = pr->positive("z_bin");
    if (pr->has("radial_bin")) prof.radial_bin = pr->positive("radial_bin");
    if (prof.z_bin == 0.0 && prof.radial_bin == 0.0) pr->fail("", "expected z_bin (slab profiles along z), radial_bin (around the colloid) or both");
    pr->reject_unless(prof.radial_bin > 0.0, "radial_max", "without radial_bin");
    pr->reject_unless(prof.radial_bin > 0.0, "midplane_half_width", "without radial_bin");
    if (pr->has("radial_max")) prof.radial_max = pr->positive("radial_max");
    prof.midplane_half_width = pr->positive("midplane_half_width", prof.midplane_half_width);
    p.profiles = prof;
  }
  // λ only changes the forces that depend on velocities: the liquid's dissipative force and the
  // colloids' and walls' friction shells.
  const bool velocity_dependent = p.liquid.gamma > 0.0 || (p.colloids && p.colloids->shell.gamma_surface > 0.0) ||
                                  (p.walls && (p.walls->gamma_surface[0] > 0.0 || p.walls->gamma_surface[1] > 0.0));
  cfg.reject_unless(velocity_dependent, "velocity_lambda", "without velocity-dependent forces (liquid.gamma 0 and no friction shell)");
  p.velocity_lambda = cfg.non_negative("velocity_lambda", p.velocity_lambda);
  if (p.velocity_lambda > 1.0) cfg.fail("velocity_lambda", "expected Groot–Warren's λ in [0, 1] (½: LAMMPS's scheme; they used 0.65)");
  if (cfg.has("frame_species")) {
    p.frame_species = cfg.strings("frame_species");
    if (p.frame_species.empty()) cfg.fail("frame_species", "expected at least one species (leave the key out for every particle)");
  }
  return p;
}

}  // namespace anisodyn

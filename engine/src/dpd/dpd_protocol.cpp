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
    p.colloids = col;
  }
  if (cfg.has("frame_species")) {
    p.frame_species = cfg.strings("frame_species");
    if (p.frame_species.empty()) cfg.fail("frame_species", "expected at least one species (leave the key out for every particle)");
  }
  return p;
}

}  // namespace anisodyn

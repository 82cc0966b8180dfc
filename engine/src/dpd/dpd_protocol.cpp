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
  return p;
}

}  // namespace anisodyn

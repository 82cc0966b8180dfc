#include "anisodyn/bd/bd_protocol.hpp"

namespace anisodyn {

namespace {
BdUnits parse_units(tool::ConfigNode& cfg) {
  BdUnits u;
  auto node = cfg.optional_object("units");
  if (!node) return u;
  u.si = node->choice("system", {"reduced", "SI"}, "reduced") == "SI";
  for (const char* key : {"length", "temperature"})
    node->reject_unless(u.si, key, "in reduced units (lengths are the input's, kT = 1)");
  if (u.si) {
    u.length_m = node->positive("length");
    u.temperature_K = node->positive("temperature");
  }
  return u;
}

BdCap parse_cap(tool::ConfigNode& caps, const std::string& key) {
  BdCap c;
  // null means "no cap", which ConfigNode::has reads as an absent key (and marks as read)
  const bool given = caps.raw().contains(key);
  if (!caps.has(key)) {
    if (given) c.kind = BdCap::Kind::None;
    return c;
  }
  if (caps.value(key).is_string()) {
    caps.choice(key, {"step_bound"});
  } else {
    c.kind = BdCap::Kind::Value;
    c.value = caps.positive(key);
  }
  return c;
}

OverlapVolumeSpec parse_overlap_volume(tool::ConfigNode& pot) {
  for (const char* key : {"exponent", "epsilon_kT", "sigma"}) pot.reject_unless(false, key, "for the overlap-volume potential (a Mie key)");
  OverlapVolumeSpec spec;
  spec.species = pot.string("species", "");
  if (pot.has("hardness")) spec.hardness = pot.positive("hardness");
  spec.interior_only = pot.choice("finite_length", {"segment_distance", "interior_only"}, "segment_distance") == "interior_only";
  if (pot.has("skin")) spec.skin = pot.positive("skin");
  return spec;
}

MieSpec parse_mie(tool::ConfigNode& pot) {
  for (const char* key : {"hardness", "finite_length"}) pot.reject_unless(false, key, "for the Mie potential (an overlap-volume key)");
  MieSpec spec;
  if (pot.has("species")) {
    spec.species = pot.strings("species");
    if (spec.species.empty()) pot.fail("species", "expected at least one sphere species");
  }
  spec.exponent = pot.number("exponent", spec.exponent);
  if (!(spec.exponent >= 12.0)) pot.fail("exponent", "expected a repulsive exponent n ≥ 12 (the attractive one is n − 1)");
  spec.epsilon_kT = pot.positive("epsilon_kT", spec.epsilon_kT);
  spec.barker_henderson = pot.choice("sigma", {"diameter", "barker_henderson"}, "diameter") == "barker_henderson";
  if (pot.has("skin")) spec.skin = pot.positive("skin");
  return spec;
}

}  // namespace

BdProtocol parse_bd_protocol(tool::ConfigNode& cfg) {
  BdProtocol p;
  static_cast<run::TimeStepRun&>(p) = run::parse_time_step_run(cfg, "BD");
  p.units = parse_units(cfg);
  p.diffusion = io::DiffusionOverrides::parse(cfg);
  if (auto sb = cfg.optional_object("slender_body")) {
    for (const auto& [name, value] : sb->raw().items()) {
      if (!name.empty() && name[0] == '_') continue;
      auto node = sb->object(name);
      SlenderBodySpec spec;
      spec.viscosity = node.positive("viscosity");
      if (node.has("diameter")) spec.diameter = node.positive("diameter");
      spec.path = sb->child_path(name);
      if (p.diffusion.entries.count(name))
        sb->fail(name, "a species whose diffusion is given once: '" + name + "' also has an entry in species");
      p.slender_body.emplace(name, spec);
    }
  }
  if (auto pot = cfg.optional_object("potential")) {
    if (pot->choice("type", {"overlap_volume", "mie"}) == "overlap_volume")
      p.potential = parse_overlap_volume(*pot);
    else
      p.sphere_potential = parse_mie(*pot);
  }
  if (auto ext = cfg.optional_object("external_torque")) {
    ExternalTorqueSpec e;
    const nlohmann::json& ids = ext->value("particles");
    if (!ids.is_array() || ids.empty()) ext->fail("particles", "expected a non-empty list of particle ids");
    for (const auto& id : ids) {
      if (!id.is_number_integer() || id.get<std::int64_t>() < 0) ext->fail("particles", "expected non-negative integer particle ids");
      e.particles.push_back(id.get<std::int64_t>());
    }
    e.torque_kT = ext->positive("torque_kT");
    e.axis = ext->vec3("axis", Vec3::UnitZ());
    if (!(e.axis.norm() > 0.0)) ext->fail("axis", "expected a non-zero direction");
    e.axis.normalize();
    e.confinement_kT = ext->non_negative("confinement_kT", 0.0);
    e.record_every = ext->positive_integer("record_every", 1);
    p.external_torque = e;
  }
  if (auto t = cfg.optional_object("tracer")) p.tracer = run::parse_pulled_tracer(*t);
  cfg.reject_unless(p.potential || p.sphere_potential || p.external_torque || p.tracer, "caps",
                    "for free particles (no potential, external torque or pulled tracer: nothing to cap)");
  if (auto caps = cfg.optional_object("caps")) {
    p.force_cap = parse_cap(*caps, "force");
    p.torque_cap = parse_cap(*caps, "torque");
  }
  return p;
}

}  // namespace anisodyn

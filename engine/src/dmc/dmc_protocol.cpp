#include "anisodyn/dmc/dmc_protocol.hpp"

#include <cmath>
#include <cstdio>
#include <set>

#include "anisodyn/core/error.hpp"
#include "anisodyn/io/species_config.hpp"

namespace anisodyn {

namespace {

DmcMoveOptions parse_moves(std::optional<tool::ConfigNode> node) {
  DmcMoveOptions m;
  if (!node) return m;
  m.rotation = node->choice("rotation", {"exponential", "sequential"}, "exponential") == "sequential"
                   ? RotationComposition::Sequential : RotationComposition::ExponentialMap;
  m.frame = node->choice("translation_frame", {"midpoint", "old"}, "midpoint") == "old" ? TranslationFrame::Old
                                                                                         : TranslationFrame::Midpoint;
  node->reject_unless(m.rotation == RotationComposition::Sequential, "sequential_order",
                      "unless moves.rotation is \"sequential\" (the exponential map rotates about all three axes at once)");
  if (m.rotation != RotationComposition::Sequential) return m;
  const std::string order = node->string("sequential_order", "TLW");
  std::set<char> seen(order.begin(), order.end());
  if (order.size() != 3 || seen != std::set<char>{'L', 'T', 'W'})
    node->fail("sequential_order", "expected the three body axes T, W, L in some order, e.g. \"TLW\"");
  for (int k = 0; k < 3; ++k) m.sequential_order[static_cast<std::size_t>(k)] = static_cast<int>(std::string("TWL").find(order[static_cast<std::size_t>(k)]));
  return m;
}

}  // namespace

DmcProtocol parse_dmc_protocol(tool::ConfigNode& cfg) {
  DmcProtocol p;
  p.seed = static_cast<std::uint64_t>(cfg.non_negative_integer("seed", 1));
  if (auto moves = cfg.optional_object("moves"))
    for (const char* key : {"rotation", "sequential_order", "translation_frame"})
      if (moves->has(key) && p.rotation_move_key.empty()) p.rotation_move_key = moves->child_path(key);
  p.moves = parse_moves(cfg.optional_object("moves"));

  auto steps = cfg.object("time_step");
  for (const auto& [name, value] : steps.raw().items()) {
    if (!name.empty() && name[0] == '_') continue;
    p.time_steps[name] = steps.positive(name);
  }
  if (p.time_steps.empty()) cfg.fail("time_step", "expected δt_MC for at least one species, e.g. {\"board\": 0.01}");

  if (auto b = cfg.optional_object("balance")) {
    const std::string mode = b->choice("mode", {"equilibrium", "per_cycle", "none"}, "equilibrium");
    p.balance = mode == "per_cycle" ? BalanceMode::PerCycle : mode == "none" ? BalanceMode::None : BalanceMode::Equilibrium;
    p.reference = b->string("reference", "");
    p.clock = b->string("clock", "");
    const bool equilibrium = p.balance == BalanceMode::Equilibrium;
    const std::string not_equilibrium = "unless balance.mode is \"equilibrium\" (the only mode with a preliminary run)";
    b->reject_unless(equilibrium, "preliminary_cycles", not_equilibrium);
    p.preliminary_cycles = equilibrium ? b->non_negative_integer("preliminary_cycles", 10000) : 0;
    const bool iterates = equilibrium && p.preliminary_cycles > 0;
    const std::string no_preliminary = equilibrium ? "with preliminary_cycles = 0 (no preliminary run)" : not_equilibrium;
    b->reject_unless(iterates, "max_iterations", no_preliminary);
    b->reject_unless(iterates, "tolerance", no_preliminary);
    if (iterates) {
      p.preliminary_iterations = static_cast<int>(b->positive_integer("max_iterations", 3));
      p.preliminary_tolerance = b->positive("tolerance", 1e-3);
    }
    for (const char* key : {"preliminary_cycles", "max_iterations", "tolerance"})
      if (b->has(key) && p.preliminary_key.empty()) p.preliminary_key = b->child_path(key);
    b->reject_unless(p.balance == BalanceMode::PerCycle, "smoothing_cycles",
                     "unless balance.mode is \"per_cycle\" (equilibrium runs average few-particle species cumulatively)");
    if (p.balance == BalanceMode::PerCycle) {
      p.smoothing_cycles = b->number("smoothing_cycles", 10.0);
      if (p.smoothing_cycles < 1.0) b->fail("smoothing_cycles", "expected a number of cycles ≥ 1");
    }
  }

  p.field = run::parse_field_config(cfg, run::FieldUse::Switchable);
  p.segments = run::parse_schedule(cfg, run::StepUnit::cycles(), p.field.initially_on);
  for (const auto& s : p.segments)
    if (s.field_on && !p.field.any())
      cfg.fail("field", "expected an orientational field or dipoles, since the schedule switches the field on");

  if (auto t = cfg.optional_object("tracer")) {
    TracerSettings ts;
    static_cast<run::PulledTracerSpec&>(ts) = run::parse_pulled_tracer(*t);
    if (t->has("a0")) {
      const auto& v = t->raw().at("a0");
      if (v.is_number()) {
        ts.a0 = TracerBathAcceptance::Fixed;
        ts.a0_value = t->positive("a0");
        if (ts.a0_value > 1.0) t->fail("a0", "expected a bath acceptance in (0, 1]");
      } else {
        ts.a0 = t->choice("a0", {"overlap_pass", "one"}) == "one" ? TracerBathAcceptance::One : TracerBathAcceptance::OverlapPass;
      }
    }
    p.tracer = ts;
  }

  p.frames = run::parse_frame_rules(cfg, run::StepUnit::cycles());
  p.observe_every = cfg.positive_integer("observe_every", 1);

  p.diffusion = io::DiffusionOverrides::parse(cfg);
  return p;
}

void check_protocol_species(const DmcProtocol& p, const State& state, const std::string& file) {
  auto index = [&](const std::string& name) { return species_index(state.species, name); };
  std::string known;
  for (const auto& s : state.species) known += (known.empty() ? "" : ", ") + s.name;
  auto require = [&](const std::string& name, const std::string& path) {
    if (index(name) < 0)
      throw InputError(file, path, "unknown species '" + name + "': expected one of the input's species (" + known + ")");
  };
  for (const auto& [name, dt] : p.time_steps) require(name, "time_step." + name);
  if (!p.reference.empty()) require(p.reference, "balance.reference");
  if (!p.clock.empty()) require(p.clock, "balance.clock");
  if (p.field.dipoles)
    for (std::size_t k = 0; k < p.field.dipoles->species.size(); ++k)
      require(p.field.dipoles->species[k], "field.dipoles.species[" + std::to_string(k) + "]");
  p.diffusion.check(state, file);
  // Keys that only act on some inputs.
  auto has_effect_nowhere = [&](const std::string& path, const std::string& why) {
    throw InputError(file, path, "no '" + path.substr(path.rfind('.') + 1) + "': it has no effect " + why);
  };
  std::vector<std::size_t> counts(state.species.size(), 0);
  for (auto sp : state.particles.species) counts[static_cast<std::size_t>(sp)]++;
  bool rotating = false;
  std::size_t populated = 0;
  for (std::size_t s = 0; s < state.species.size(); ++s) {
    populated += counts[s] > 0 ? 1 : 0;
    rotating = rotating || (counts[s] > 0 && state.species[s].shape.is_anisotropic());
  }
  if (!p.rotation_move_key.empty() && !rotating)
    has_effect_nowhere(p.rotation_move_key, "on an input without anisotropic particles (spheres only translate)");
  if (!p.preliminary_key.empty() && populated < 2 && !p.tracer)
    has_effect_nowhere(p.preliminary_key, "on an input with a single species and no pulled tracer (there is nothing to balance)");
  if (p.tracer) {
    require(p.tracer->species, "tracer.species");
    run::find_pulled_tracer(*p.tracer, state, file);
  }

}

}  // namespace anisodyn

#include "anisodyn/mc/protocol_config.hpp"
#include "anisodyn/run/field_config.hpp"
#include "anisodyn/run/frame_rules.hpp"

#include <initializer_list>
#include <string>

namespace anisodyn {

namespace {
BoxMoves parse_box_moves(tool::ConfigNode& n) {
  return n.choice("box_moves", {"isotropic", "per_axis"}, "isotropic") == "isotropic" ? BoxMoves::Isotropic : BoxMoves::PerAxis;
}

/// Keys of one phase type or compression method, refused elsewhere with the reason why.
void reject_keys_of(tool::ConfigNode& n, bool applies, std::initializer_list<const char*> keys, const std::string& reason) {
  for (const char* key : keys) n.reject_unless(applies, key, reason);
}

McPhase parse_phase(tool::ConfigNode n, std::size_t index) {
  McPhase p;
  const std::string type = n.choice("type", {"compress", "npt", "nvt"});
  p.label = n.string("label", type + "-" + std::to_string(index));
  p.expect_phase = n.choice("expect_phase", {"", "isotropic", "nematic"}, "");
  const std::string in_phase = "in a \"" + type + "\" phase";
  reject_keys_of(n, type == "compress", {"packing_fraction", "method", "quick_step", "pressure_start", "pressure_growth",
                                         "cycles_per_step", "plateau_tolerance", "squeeze_window", "squeeze_sweeps", "max_cycles"},
                 in_phase + " (compression only)");
  reject_keys_of(n, type == "npt", {"pressure"}, in_phase + " (npt phases only; compression ramps its own pressure)");
  reject_keys_of(n, type != "compress", {"cycles"}, in_phase + " (a compression runs until it reaches its packing fraction)");
  reject_keys_of(n, type != "nvt", {"box_moves"}, in_phase + " (the box is fixed)");
  if (type == "compress") {
    p.type = McPhase::Type::Compress;
    p.target_packing_fraction = n.positive("packing_fraction");
    if (p.target_packing_fraction >= 1.0) n.fail("packing_fraction", "expected a packing fraction below 1");
    p.method = n.choice("method", {"npt", "quick"}, "npt");
    const bool quick = p.method == "quick";
    reject_keys_of(n, !quick, {"pressure_start", "pressure_growth", "cycles_per_step", "plateau_tolerance", "squeeze_window", "box_moves"},
                   "with method \"quick\" (no pressure ramp: the box shrinks by quick_step)");
    reject_keys_of(n, quick, {"quick_step"}, "unless method is \"quick\"");
    if (n.has("pressure_start")) p.pressure_start = n.positive("pressure_start");
    p.pressure_growth = n.positive("pressure_growth", 1.5);
    if (p.pressure_growth <= 1.0) n.fail("pressure_growth", "expected a factor greater than 1");
    p.cycles_per_step = n.positive_integer("cycles_per_step", 200);
    p.max_cycles = n.positive_integer("max_cycles", 1000000);
    p.squeeze_sweeps = n.positive_integer("squeeze_sweeps", 5);
    p.squeeze_window = n.non_negative("squeeze_window", 0.02);
    p.plateau_tolerance = n.non_negative("plateau_tolerance", 0.005);
    p.box_moves = parse_box_moves(n);
    p.tune = n.boolean("tune", true);
    p.quick_step = n.positive("quick_step", 0.005);
    if (p.quick_step >= 0.5) n.fail("quick_step", "expected a relative volume step below 0.5");
  } else if (type == "npt") {
    p.type = McPhase::Type::Npt;
    p.pressure = n.positive("pressure");
    p.cycles = n.positive_integer("cycles");
    p.box_moves = parse_box_moves(n);
    p.tune = n.boolean("tune", false);
  } else {
    p.type = McPhase::Type::Nvt;
    p.cycles = n.positive_integer("cycles");
    p.tune = n.boolean("tune", false);
  }
  return p;
}
}  // namespace

McProtocol parse_mc_protocol(tool::ConfigNode& cfg) {
  McProtocol p;
  p.seed = static_cast<std::uint64_t>(cfg.non_negative_integer("seed", 1));
  p.target_acceptance = cfg.positive("target_acceptance", 0.35);
  if (p.target_acceptance >= 1.0) cfg.fail("target_acceptance", "expected an acceptance between 0 and 1");
  p.tune_every = cfg.positive_integer("tune_every", 100);
  p.observe_every = cfg.positive_integer("observe_every", 10);
  p.domain_sweeps = cfg.choice("sweeps", {"sequential", "domains"}, "sequential") == "domains";
  p.frames = run::parse_frame_rules(cfg, run::StepUnit::cycles(), run::FrameUse::Preparation);
  p.field = run::parse_field_config(cfg, run::FieldUse::Constant).orientational;
  auto phases = cfg.objects("phases");
  if (phases.empty()) cfg.fail("phases", "expected at least one phase (compress, npt or nvt)");
  for (std::size_t i = 0; i < phases.size(); ++i) p.phases.push_back(parse_phase(phases[i], i));
  bool tunes = false;
  for (const auto& phase : p.phases) tunes = tunes || phase.tune;
  for (const char* key : {"target_acceptance", "tune_every"})
    cfg.reject_unless(tunes, key, "when no phase tunes its move sizes (set \"tune\": true in a phase)");
  return p;
}

}  // namespace anisodyn

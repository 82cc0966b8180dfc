#include "anisodyn/mc/protocol.hpp"
#include "anisodyn/geometry/body_axes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "anisodyn/core/error.hpp"
#include "anisodyn/core/progress.hpp"
#include "anisodyn/core/signals.hpp"
#include "anisodyn/core/statistics.hpp"
#include "anisodyn/interactions/hard_overlap.hpp"
#include "anisodyn/system/order.hpp"

namespace anisodyn {

namespace {
const char* type_name(McPhase::Type t) {
  switch (t) {
    case McPhase::Type::Compress: return "compress";
    case McPhase::Type::Npt: return "npt";
    case McPhase::Type::Nvt: return "nvt";
  }
  return "?";
}

std::string format_mean_error(const nlohmann::json& stats) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4f ± %.4f", stats["mean"].get<double>(), stats["error"].get<double>());
  return buf;
}

/// MC has no physical time: its trajectories count time in cycles.
constexpr double kTimePerCycle = 1.0;
// The squeeze's relative volume steps: at most 0.1% (spec 10 §3.2), halved down to this floor.
constexpr double kLargestSqueezeStep = 1e-3;
constexpr double kSmallestSqueezeStep = 1e-9;

std::string phase_detail(const State& s, const McEngine& e) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "eta=%.4f dlnV=%.3g", s.packing_fraction(), e.move_sizes().log_volume);
  return buf;
}
}  // namespace

McRunner::McRunner(State& state, const McProtocol& protocol, bool quiet)
    : state_(state),
      protocol_(protocol),
      engine_(state, RngState{protocol.seed, protocol.replica, 0, 4}),
      quiet_(quiet),
      loop_(state, *this, protocol.frames, protocol.observe_every) {
  engine_.set_field(protocol.field);
  engine_.set_domain_sweeps(protocol.domain_sweeps);
  tune_mark_ = sample_mark_ = engine_.counters();
  summary_["phases"] = nlohmann::json::array();
}

void McRunner::record(io::H5mdWriter& out, const std::string& name, const std::vector<double>& values, const std::string& definition) {
  out.append_observable(name, loop_.step(), loop_.time(), values);
  if (described_.insert(name).second) {
    out.set_observable_attribute(name, "definition", definition);
    out.set_observable_attribute(name, "units", name == "box_edges" ? "length unit of the study" : "1");
  }
  PhaseSeries& s = phase_samples_[name];
  s.width = values.size();
  s.value.insert(s.value.end(), values.begin(), values.end());
}

void McRunner::observe(io::H5mdWriter& out, std::int64_t, double) {
  const MoveCounters w = engine_.counters().since(sample_mark_);
  sample_mark_ = engine_.counters();
  const Vec3& L = state_.box.edges();
  record(out, "packing_fraction", {state_.packing_fraction()}, "packing fraction: total particle volume / box volume");
  record(out, "box_edges", {L.x(), L.y(), L.z()}, "box edge lengths Lx, Ly, Lz");
  const McPhase& phase = protocol_.phases[cursor_.phase];
  const bool npt = phase.type == McPhase::Type::Npt || (phase.type == McPhase::Type::Compress && !cursor_.squeezing);
  const double pressure = phase.type == McPhase::Type::Npt ? phase.pressure : cursor_.compress_pressure;
  record(out, "pressure", {npt ? pressure : std::numeric_limits<double>::quiet_NaN()}, "imposed reduced pressure βP (NaN at constant volume)");
  if (w.volume_tried > 0)
    record(out, "acceptance_volume", {MoveCounters::ratio(w.volume_accepted, w.volume_tried)}, "acceptance of volume moves since the previous sample");
  for (std::size_t s = 0; s < state_.species.size(); ++s) {
    const auto& sp = state_.species[s];
    record(out, "acceptance_" + sp.name,
           {MoveCounters::ratio(w.translate_accepted[s], w.translate_tried[s]), MoveCounters::ratio(w.rotate_accepted[s], w.rotate_tried[s])},
           "acceptance of translation and rotation trials since the previous sample");
    if (!sp.shape.is_anisotropic()) continue;
    const auto order = body_axis_order(state_, static_cast<int>(s));
    record(out, "order_" + sp.name, {order[0].order, order[1].order, order[2].order},
           "uniaxial order parameters U_T, U_W, U_L: largest eigenvalue of the Q tensor of each body axis");
  }
  if (protocol_.field.active())
    record(out, "field_energy", {engine_.field_energy() / static_cast<double>(state_.particles.size())}, "field energy per particle βU/N");
}

double McRunner::advance() {
  sweep_.step(state_);
  ++cursor_.cycle_in_phase;
  tune_if_due();
  return kTimePerCycle;
}

double McRunner::advance_steps(std::int64_t k) {
  for (std::int64_t done = 0; done < k;) done += engine_.cycles(static_cast<int>(k - done));
  cursor_.cycle_in_phase += k;
  tune_if_due();  // the batch ends at a tuning point, if it reaches one
  return kTimePerCycle;
}

void McRunner::tune_if_due() {
  if (protocol_.phases[cursor_.phase].tune && cursor_.cycle_in_phase % protocol_.tune_every == 0) {
    engine_.tune(protocol_.target_acceptance, engine_.counters().since(tune_mark_));
    tune_mark_ = engine_.counters();
  }
}

void McRunner::one_cycle(io::H5mdWriter& out) {
  loop_.step(out);
  checkpoints_->tick(loop_.step(), "cycle " + std::to_string(loop_.step()));
}

void McRunner::cycles_at_once(io::H5mdWriter& out, std::int64_t most) {
  if (!engine_.domain_sweeps()) {  // only domain sweeps run cycles in batches
    one_cycle(out);
    return;
  }
  std::int64_t k = std::min<std::int64_t>(most, DomainSweep::kCyclesPerCut);
  if (protocol_.phases[cursor_.phase].tune)
    k = std::min(k, protocol_.tune_every - cursor_.cycle_in_phase % protocol_.tune_every);
  if (const std::int64_t every = checkpoints_->every(); every > 0) k = std::min(k, every - loop_.step() % every);
  loop_.steps(out, loop_.quiet_steps(k, kTimePerCycle));
  checkpoints_->tick(loop_.step(), "cycle " + std::to_string(loop_.step()));
}

void McRunner::run_fixed_phase(io::H5mdWriter& out, const McPhase& phase) {
  if (phase.type == McPhase::Type::Npt) engine_.set_pressure(phase.pressure, phase.box_moves);
  else engine_.set_pressure(std::nullopt);
  Progress progress(std::string("mc ") + type_name(phase.type) + " " + phase.label, phase.cycles, quiet_);
  while (cursor_.cycle_in_phase < phase.cycles) {
    cycles_at_once(out, phase.cycles - cursor_.cycle_in_phase);
    progress.update(cursor_.cycle_in_phase, phase_detail(state_, engine_));
  }
  progress.finish(phase_detail(state_, engine_));
}

void McRunner::run_quick_compress(io::H5mdWriter& out, const McPhase& phase) {
  const double target_volume = state_.packing_fraction() * state_.box.volume() / phase.target_packing_fraction;
  const double reach = largest_pair_cutoff(state_.species);
  if ((state_.box.edges() * std::cbrt(target_volume / state_.box.volume())).minCoeff() < 2.0 * reach)
    throw RuntimeFailure("packing fraction " + std::to_string(phase.target_packing_fraction) +
                         " needs a box smaller than twice the largest cut-off (minimum image): use more particles");
  engine_.set_pressure(std::nullopt);
  if (cursor_.quick_step <= 0.0) cursor_.quick_step = phase.quick_step;
  Progress progress("mc quick compress to eta=" + std::to_string(phase.target_packing_fraction), phase.max_cycles, quiet_);
  // Checkpoints and interrupts only here, between a squeeze and the next shrink, where the
  // configuration has no overlaps and the cursor says exactly where the loop stands; a resumed run
  // then shrinks, removes and squeezes as the uninterrupted one. An interrupt during the removal or
  // the squeeze goes back here.
  std::int64_t last_checkpoint = loop_.step();
  while (state_.box.volume() > target_volume * (1.0 + 1e-12)) {
    const std::int64_t every = checkpoints_->every();
    const bool due = every > 0 && loop_.step() - last_checkpoint >= every;
    checkpoints_->tick_if(due, "cycle " + std::to_string(loop_.step()));
    if (due) last_checkpoint = loop_.step();
    const ValidPoint before_shrink = valid_point();
    engine_.rescale_allowing_overlaps(std::max(target_volume, state_.box.volume() * (1.0 - cursor_.quick_step)));
    engine_.set_overlap_removal(true);
    std::int64_t sweeps = 0;
    while (engine_.overlap().any_overlap()) {
      loop_.step(out);
      ++sweeps;
      if (interrupt_requested()) interrupt_at(before_shrink);
      if (cursor_.cycle_in_phase >= phase.max_cycles)
        throw RuntimeFailure("quick compression did not reach packing fraction " + std::to_string(phase.target_packing_fraction) +
                             " within " + std::to_string(phase.max_cycles) + " cycles (reached " + std::to_string(state_.packing_fraction()) + ")");
    }
    engine_.set_overlap_removal(false);
    // Removal leaves particles just touching; ordinary sweeps reopen the gaps before the next
    // shrink (without them each shrink creates more overlaps and the compression stalls).
    for (std::int64_t k = 0; k < phase.squeeze_sweeps; ++k) {
      loop_.step(out);
      if (interrupt_requested()) interrupt_at(before_shrink);
    }
    // Adapt the step: a few sweeps per shrink keeps the particles close to a relaxed packing.
    if (sweeps <= 3) cursor_.quick_step = std::min(0.05, 1.5 * cursor_.quick_step);
    else if (sweeps > 20) cursor_.quick_step = std::max(1e-4, 0.7 * cursor_.quick_step);
    progress.update(cursor_.cycle_in_phase, phase_detail(state_, engine_) + " step=" + std::to_string(cursor_.quick_step));
  }
  progress.finish(phase_detail(state_, engine_));
}

void McRunner::interrupt_at(const ValidPoint& p) {
  // The engine's own structures are not brought back: the run stops here.
  state_.particles = p.particles;
  state_.box = p.box;
  restore(p.runner);
  checkpoints_->tick(loop_.step(), "cycle " + std::to_string(loop_.step()) + " (before the quick-compression step under way)");
  throw Interrupted("interrupted during quick compression");  // tick() has thrown already
}

void McRunner::run_compress_phase(io::H5mdWriter& out, const McPhase& phase) {
  if (phase.method == "quick") return run_quick_compress(out, phase);
  const double target = phase.target_packing_fraction;
  const double target_volume = state_.packing_fraction() * state_.box.volume() / target;
  Progress progress("mc compress to eta=" + std::to_string(target), phase.max_cycles, quiet_);
  auto check_budget = [&] {
    if (cursor_.cycle_in_phase >= phase.max_cycles)
      throw RuntimeFailure("compression did not reach packing fraction " + std::to_string(target) + " within " +
                           std::to_string(phase.max_cycles) + " cycles (reached " + std::to_string(state_.packing_fraction()) +
                           " at betaP=" + std::to_string(cursor_.compress_pressure) + "); raise max_cycles or lower the target");
  };
  if (!cursor_.squeezing) {
    if (cursor_.compress_pressure <= 0.0)
      // Default: the ideal-gas pressure at the target density, a safe underestimate of the real one.
      cursor_.compress_pressure = phase.pressure_start.value_or(static_cast<double>(state_.particles.size()) / target_volume);
    // Raise βP only while η rises more slowly than the target rate (plateau_tolerance per step): a
    // fixed schedule outruns the slow volume relaxation of large systems and sends βP to absurd
    // values, which jams the particles. βP is also capped at 50× the ideal-gas value at the target.
    while (state_.packing_fraction() < target * (1.0 - phase.squeeze_window)) {
      engine_.set_pressure(cursor_.compress_pressure, phase.box_moves);
      const double eta_before = state_.packing_fraction();
      const std::int64_t step_end = (cursor_.cycle_in_phase / phase.cycles_per_step + 1) * phase.cycles_per_step;
      while (cursor_.cycle_in_phase < step_end) {
        one_cycle(out);
        progress.update(cursor_.cycle_in_phase, phase_detail(state_, engine_) + " betaP=" + std::to_string(cursor_.compress_pressure));
      }
      check_budget();
      const double eta_after = state_.packing_fraction();
      const double cap = 50.0 * static_cast<double>(state_.particles.size()) / target_volume;
      if (eta_after < target * (1.0 - phase.squeeze_window) && eta_after < eta_before * (1.0 + phase.plateau_tolerance))
        cursor_.compress_pressure = std::min(cap, cursor_.compress_pressure * phase.pressure_growth);
    }
    cursor_.squeezing = true;
  }
  engine_.set_pressure(std::nullopt);
  // Squeeze: affine steps of at most 0.1% in volume. A step of relative size s creates no overlap
  // with a chance of about exp[−(βPV − N) s]: fixed 0.1% steps never succeed for a few thousand
  // dense particles (2000 rods 12×1×1 at η = 0.34: about 1e−8). So a step that would overlap is
  // halved, and the configuration relaxed by sweeps; one that succeeds is doubled, up to 0.1%. The
  // steps settle where about half succeed.
  if (cursor_.squeeze_step <= 0.0) cursor_.squeeze_step = kLargestSqueezeStep;
  while (std::abs(state_.box.volume() - target_volume) > 1e-12 * target_volume) {
    const double v = state_.box.volume();
    const double next = v < target_volume ? target_volume : std::max(target_volume, v * (1.0 - cursor_.squeeze_step));
    if (engine_.try_rescale(next)) {
      cursor_.squeeze_step = std::min(kLargestSqueezeStep, 2.0 * cursor_.squeeze_step);
      continue;
    }
    cursor_.squeeze_step = std::max(kSmallestSqueezeStep, 0.5 * cursor_.squeeze_step);
    for (std::int64_t k = 0; k < phase.squeeze_sweeps; ++k) one_cycle(out);
    check_budget();
    progress.update(cursor_.cycle_in_phase, phase_detail(state_, engine_) + " squeezing");
  }
  progress.finish(phase_detail(state_, engine_));
}

void McRunner::summarise_phase(const McPhase& phase, std::int64_t first_step) {
  nlohmann::json js;
  js["type"] = type_name(phase.type);
  js["label"] = phase.label;
  js["first_cycle"] = first_step;
  js["last_cycle"] = loop_.step();
  js["final_packing_fraction"] = state_.packing_fraction();
  js["final_box_edges"] = {state_.box.edges().x(), state_.box.edges().y(), state_.box.edges().z()};
  if (phase.type == McPhase::Type::Npt) js["pressure"] = phase.pressure;
  if (phase.type == McPhase::Type::Compress) js["final_ramp_pressure"] = cursor_.compress_pressure;

  // Column k of an observable over the samples taken in this phase.
  auto column = [&](const std::string& name, std::size_t k) {
    std::vector<double> out;
    auto it = phase_samples_.find(name);
    if (it == phase_samples_.end()) return out;
    const PhaseSeries& s = it->second;
    for (std::size_t r = k; r < s.value.size(); r += s.width) out.push_back(s.value[r]);
    return out;
  };
  auto stats = [](const std::vector<double>& x) {
    const MeanError m = block_average(x);
    // Drift: compare the halves; a difference beyond 3 combined errors means not yet stationary.
    const std::vector<double> a(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(x.size() / 2));
    const std::vector<double> b(x.begin() + static_cast<std::ptrdiff_t>(x.size() / 2), x.end());
    const MeanError ma = block_average(a), mb = block_average(b);
    const bool drift = x.size() >= 64 && std::abs(ma.mean - mb.mean) > 3.0 * std::hypot(ma.error, mb.error);
    return nlohmann::json{{"mean", m.mean},
                          {"error", m.error},
                          {"error_blocking", m.error_blocking},
                          {"error_autocorrelation", m.error_autocorrelation},
                          {"tau_int_samples", m.tau_int},
                          {"samples", m.samples},
                          {"blocks", m.blocks},
                          {"drifting", drift}};
  };
  js["packing_fraction"] = stats(column("packing_fraction", 0));
  bool nematic = false;
  for (const auto& sp : state_.species) {
    js["acceptance"][sp.name] = {{"translate", stats(column("acceptance_" + sp.name, 0))["mean"]}};
    if (!sp.shape.is_anisotropic()) continue;
    js["acceptance"][sp.name]["rotate"] = stats(column("acceptance_" + sp.name, 1))["mean"];
    for (std::size_t k = 0; k < 3; ++k) {
      auto st = stats(column("order_" + sp.name, k));
      nematic = nematic || st["mean"].get<double>() > kNematicThreshold;
      js["order"][sp.name][body_axis_name(k)] = st;
    }
    std::size_t n = 0;
    for (auto s : state_.particles.species) n += (state_.species[static_cast<std::size_t>(s)].name == sp.name);
    js["order"][sp.name]["isotropic_baseline"] = isotropic_order_baseline(n, 50);
  }
  if (js.contains("order")) {
    js["phase"] = nematic ? "nematic" : "isotropic";
    if (!phase.expect_phase.empty() && phase.expect_phase != js["phase"]) {
      js["phase_mismatch"] = true;
      std::fprintf(stderr, "anisodyn-mc: WARNING: phase '%s' expected after %s phase '%s', but the order parameters say '%s'\n",
                   phase.expect_phase.c_str(), type_name(phase.type), phase.label.c_str(), js["phase"].get<std::string>().c_str());
    }
  }
  if (!quiet_) {
    std::string line = "mc " + std::string(type_name(phase.type)) + " " + phase.label + ": eta = " +
                       format_mean_error(js["packing_fraction"]);
    if (js.contains("order"))
      for (const auto& [name, axes] : js["order"].items())
        line += "; " + name + " U_T, U_W, U_L = " + format_mean_error(axes["T"]) + ", " + format_mean_error(axes["W"]) + ", " +
                format_mean_error(axes["L"]) + " (random-orientation baseline " + std::to_string(axes["isotropic_baseline"].get<double>()).substr(0, 5) + ")";
    if (js.contains("phase")) line += " -> " + js["phase"].get<std::string>();
    std::fprintf(stderr, "%s\n", line.c_str());
  }
  const MoveSizes& m = engine_.move_sizes();
  js["move_sizes"] = {{"translate", m.translate}, {"rotate", m.rotate}, {"log_volume", m.log_volume}};
  summary_["phases"].push_back(js);
}

void McRunner::run(io::H5mdWriter& out, std::int64_t checkpoint_every, const std::function<void()>& checkpoint) {
  run::CheckpointClock checkpoints(checkpoint_every, checkpoint);
  checkpoints_ = &checkpoints;
  for (; cursor_.phase < protocol_.phases.size(); ++cursor_.phase) {
    const McPhase& phase = protocol_.phases[cursor_.phase];
    const std::int64_t first_step = loop_.step() - cursor_.cycle_in_phase;
    if (cursor_.cycle_in_phase == 0) tune_mark_ = engine_.counters();
    if (phase.type == McPhase::Type::Compress) run_compress_phase(out, phase);
    else run_fixed_phase(out, phase);
    summarise_phase(phase, first_step);
    phase_samples_.clear();
    cursor_.cycle_in_phase = 0;
    cursor_.compress_pressure = 0.0;
    cursor_.squeezing = false;
    cursor_.quick_step = 0.0;
    cursor_.squeeze_step = 0.0;
  }
  loop_.finish(out, false);  // the samples are snapshots every observe_every cycles: no remainder row
  summary_["total_cycles"] = loop_.step();
  summary_["final_packing_fraction"] = state_.packing_fraction();
}

}  // namespace anisodyn

namespace anisodyn {

namespace {
nlohmann::json counters_to_json(const MoveCounters& c) {
  return {{"translate_tried", c.translate_tried}, {"translate_accepted", c.translate_accepted},
          {"rotate_tried", c.rotate_tried},       {"rotate_accepted", c.rotate_accepted},
          {"volume_tried", c.volume_tried},       {"volume_accepted", c.volume_accepted}};
}
/// The domain sweeps' layout (null: slabs along random axes; absent: not chosen yet) and the cut
/// in use (null between cuts).
nlohmann::json domains_to_json(const DomainSweep& d) {
  nlohmann::json j = nlohmann::json::object();
  if (d.layout_chosen()) j["layout"] = d.layout() ? nlohmann::json(*d.layout()) : nlohmann::json(nullptr);
  const auto& cut = d.cut();
  j["cut"] = cut ? nlohmann::json{{"count", cut->count},
                                  {"offset", {cut->offset.x(), cut->offset.y(), cut->offset.z()}},
                                  {"cycles_done", cut->cycles_done}}
                 : nlohmann::json(nullptr);
  return j;
}
void domains_from_json(const nlohmann::json& j, DomainSweep& d) {
  if (j.contains("layout"))
    d.set_layout(j.at("layout").is_null() ? std::nullopt : std::optional<DomainSweep::Layout>(j.at("layout").get<DomainSweep::Layout>()));
  const auto& c = j.at("cut");
  if (c.is_null()) return d.restore_cut(std::nullopt);
  DomainSweep::Cut cut;
  cut.count = c.at("count").get<DomainSweep::Layout>();
  const auto offset = c.at("offset").get<std::array<double, 3>>();
  cut.offset = Vec3(offset[0], offset[1], offset[2]);
  cut.cycles_done = c.at("cycles_done").get<int>();
  d.restore_cut(cut);
}
MoveCounters counters_from_json(const nlohmann::json& j) {
  MoveCounters c;
  j.at("translate_tried").get_to(c.translate_tried);
  j.at("translate_accepted").get_to(c.translate_accepted);
  j.at("rotate_tried").get_to(c.rotate_tried);
  j.at("rotate_accepted").get_to(c.rotate_accepted);
  j.at("volume_tried").get_to(c.volume_tried);
  j.at("volume_accepted").get_to(c.volume_accepted);
  return c;
}
}  // namespace

nlohmann::json McRunner::checkpoint_state() const {
  const RngState& r = engine_.rng_state();
  const MoveSizes& m = engine_.move_sizes();
  return {{"cursor", {{"phase", cursor_.phase}, {"cycle_in_phase", cursor_.cycle_in_phase},
                      {"compress_pressure", cursor_.compress_pressure}, {"squeezing", cursor_.squeezing},
                      {"quick_step", cursor_.quick_step}, {"squeeze_step", cursor_.squeeze_step}}},
          {"rng", {{"seed", r.seed}, {"stream", r.stream}, {"counter", r.counter}, {"used", r.used}}},
          {"counters", counters_to_json(engine_.counters())},
          {"domain_sweeps", engine_.domain_sweep() ? domains_to_json(*engine_.domain_sweep()) : nlohmann::json(nullptr)},
          {"volume_moves_owed", engine_.volume_moves_owed()},
          {"tune_mark", counters_to_json(tune_mark_)},
          {"sample_mark", counters_to_json(sample_mark_)},
          {"move_sizes", {{"translate", m.translate}, {"rotate", m.rotate}, {"log_volume", m.log_volume}}},
          {"loop", loop_.checkpoint_state()},
          {"summary", summary_}};
}

void McRunner::restore(const nlohmann::json& js) {
  const auto& c = js.at("cursor");
  cursor_.phase = c.at("phase").get<std::size_t>();
  cursor_.cycle_in_phase = c.at("cycle_in_phase").get<std::int64_t>();
  cursor_.compress_pressure = c.at("compress_pressure").get<double>();
  cursor_.squeezing = c.at("squeezing").get<bool>();
  cursor_.quick_step = c.at("quick_step").get<double>();
  // Checkpoints from before the squeeze adapted its step have none: start again at the largest.
  cursor_.squeeze_step = c.value("squeeze_step", 0.0);
  const auto& r = js.at("rng");
  RngState rng{r.at("seed").get<std::uint64_t>(), r.at("stream").get<std::uint64_t>(), r.at("counter").get<std::uint64_t>(),
               r.at("used").get<std::uint32_t>()};
  MoveSizes m;
  js.at("move_sizes").at("translate").get_to(m.translate);
  js.at("move_sizes").at("rotate").get_to(m.rotate);
  m.log_volume = js.at("move_sizes").at("log_volume").get<double>();
  // Checkpoints from before domain sweeps deferred their volume moves to the cut's end owe none.
  engine_.restore(rng, counters_from_json(js.at("counters")), m, js.value("volume_moves_owed", 0));
  // Checkpoints written before domain sweeps kept a cut for several cycles have none: the next
  // cycle starts a new cut.
  if (DomainSweep* d = engine_.domain_sweep(); d && js.contains("domain_sweeps") && !js.at("domain_sweeps").is_null())
    domains_from_json(js.at("domain_sweeps"), *d);
  tune_mark_ = counters_from_json(js.at("tune_mark"));
  sample_mark_ = counters_from_json(js.at("sample_mark"));
  summary_ = js.at("summary");
  loop_.restore(js.at("loop"));
}

void McRunner::restore_phase_samples(const io::H5mdReader& partial) {
  const std::int64_t first_step = loop_.step() - cursor_.cycle_in_phase;
  phase_samples_.clear();
  for (const auto& name : partial.observable_names()) {
    const auto series = partial.read_observable(name);
    PhaseSeries& s = phase_samples_[name];
    s.width = series.width;
    for (std::size_t r = 0; r < series.rows(); ++r)
      if (series.step[r] > first_step && series.step[r] <= loop_.step())
        s.value.insert(s.value.end(), series.value.begin() + static_cast<std::ptrdiff_t>(r * s.width),
                       series.value.begin() + static_cast<std::ptrdiff_t>((r + 1) * s.width));
  }
}

}  // namespace anisodyn

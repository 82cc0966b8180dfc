#include "anisodyn/dmc/dmc_runner.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "anisodyn/core/error.hpp"
#include "anisodyn/core/progress.hpp"
#include "anisodyn/core/signals.hpp"
#include "anisodyn/system/order.hpp"

namespace anisodyn {

namespace {
const char* kAxisLetters = "TWL";

nlohmann::json counts_json(const std::vector<TrialCounts>& v) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& c : v) j.push_back({c.tried, c.passed, c.accepted});
  return j;
}

std::vector<TrialCounts> counts_from_json(const nlohmann::json& j) {
  std::vector<TrialCounts> v;
  for (const auto& r : j) v.push_back(TrialCounts{r[0].get<std::int64_t>(), r[1].get<std::int64_t>(), r[2].get<std::int64_t>()});
  return v;
}

std::vector<std::size_t> species_counts(const State& s) {
  std::vector<std::size_t> n(s.species.size(), 0);
  for (auto sp : s.particles.species) n[static_cast<std::size_t>(sp)]++;
  return n;
}

run::ProductionSettings production_settings(const DmcProtocol& p) {
  return {p.segments, p.frames, p.observe_every, run::StepUnit::cycles(), "dmc production"};
}

/// Relative validity parameter of the pulled-tracer scheme above which results drift (spec 10 §4.5).
constexpr double kTracerValidityLimit = 0.2;
}  // namespace

std::int64_t DmcRunner::species_index(const std::string& name) const { return anisodyn::species_index(state_.species, name); }

DmcRunner::DmcRunner(State& state, const DmcProtocol& protocol, const std::string& config_file, bool quiet)
    : state_(state),
      protocol_(protocol),
      config_file_(config_file),
      quiet_(quiet),
      engine_((check_protocol_species(protocol, state, config_file), state), RngState{protocol.seed, protocol.replica, 0, 4},
              protocol.moves),
      production_(state, *this, production_settings(protocol), quiet) {
  configure_species();
  configure_fields();
}

void DmcRunner::configure_species() {
  const std::size_t ns = state_.species.size();
  const auto counts = species_counts(state_);
  summary_["warnings"] = nlohmann::json::array();

  protocol_.diffusion.apply(state_.species);
  for (std::size_t s = 0; s < ns; ++s) {
    const Species& sp = state_.species[s];
    if (counts[s] == 0) continue;
    if (!(sp.D_trans.minCoeff() > 0.0))
      throw InputError(config_file_, "species." + sp.name + ".D_trans",
                       "expected positive translational diffusion coefficients for species '" + sp.name +
                           "' (none in the input's species table): give them here or in the species file");
    if (sp.shape.is_anisotropic() && !(sp.D_rot.minCoeff() > 0.0))
      throw InputError(config_file_, "species." + sp.name + ".D_rot",
                       "expected positive rotational diffusion coefficients for the anisotropic species '" + sp.name + "'");
  }

  // Tracer, reference and clock.
  if (protocol_.tracer) {
    tracer_species_ = static_cast<int>(species_index(protocol_.tracer->species));
    PulledTracer t;
    const std::size_t particle = run::find_pulled_tracer(*protocol_.tracer, state_, config_file_);
    t.particle = static_cast<std::int32_t>(particle);
    t.axis = protocol_.tracer->axis;
    t.beta_force = run::pulled_tracer_beta_force(*protocol_.tracer, state_, particle);
    engine_.set_tracer(t);
  }
  int reference = 0;
  if (!protocol_.reference.empty()) reference = static_cast<int>(species_index(protocol_.reference));
  else if (tracer_species_ >= 0) reference = tracer_species_;
  else if (protocol_.time_steps.size() == 1) reference = static_cast<int>(species_index(protocol_.time_steps.begin()->first));
  else if (ns > 1 && protocol_.balance != BalanceMode::None)
    throw InputError(config_file_, "balance.reference", "expected the reference species whose time step is fixed (several time steps are given)");
  const std::string& ref_name = state_.species[static_cast<std::size_t>(reference)].name;
  if (!protocol_.time_steps.count(ref_name))
    throw InputError(config_file_, "time_step." + ref_name, "expected the time step δt_MC of the reference species '" + ref_name + "'");
  dt_.assign(ns, protocol_.time_steps.at(ref_name));
  for (std::size_t s = 0; s < ns; ++s) {
    const auto it = protocol_.time_steps.find(state_.species[s].name);
    if (it != protocol_.time_steps.end()) dt_[s] = it->second;
    else if (protocol_.balance == BalanceMode::None && counts[s] > 0)
      throw InputError(config_file_, "time_step." + state_.species[s].name,
                       "expected a time step for every species when balance.mode is \"none\"");
  }
  int clock = 0;
  if (!protocol_.clock.empty()) clock = static_cast<int>(species_index(protocol_.clock));
  else
    for (std::size_t s = 0; s < ns; ++s)
      if (counts[s] > counts[static_cast<std::size_t>(clock)]) clock = static_cast<int>(s);

  TimeBalanceSettings b;
  b.mode = protocol_.balance;
  b.reference = reference;
  b.clock = clock;
  b.tracer_species = tracer_species_;
  if (protocol_.tracer) {
    b.a0 = protocol_.tracer->a0;
    b.a0_value = protocol_.tracer->a0_value;
  }
  b.smoothing_cycles = protocol_.smoothing_cycles;
  b.species_counts = counts;
  balance_ = std::make_unique<TimeBalance>(b);
  engine_.set_time_steps(dt_);

  preliminary_totals_.assign(ns, TrialCounts{});
  production_totals_.assign(ns, TrialCounts{});
  window_.assign(ns, TrialCounts{});
  window_balance_.clear(ns);
  production_balance_.clear(ns);
}

void DmcRunner::configure_fields() {
  engine_.set_orientational_field(protocol_.field.orientational);
  if (const auto& dipoles = protocol_.field.dipoles) {
    DipoleSettings d;
    d.gamma = dipoles->gamma;
    d.species_carries.assign(state_.species.size(), 0);
    std::size_t n_dipoles = 0;
    for (const auto& name : dipoles->species) d.species_carries[static_cast<std::size_t>(species_index(name))] = 1;
    for (auto sp : state_.particles.species) n_dipoles += d.species_carries[static_cast<std::size_t>(sp)] ? 1 : 0;
    try {
      d.ewald = choose_ewald_parameters(state_.box.edges(), n_dipoles, dipoles->accuracy);
    } catch (const InputError& e) {
      throw InputError(config_file_, "field.dipoles.accuracy", e.what());
    }
    d.ewald.minimum_image_only = dipoles->minimum_image_only;
    engine_.set_dipoles(d, protocol_.field.orientational.direction);
    summary_["ewald"] = {{"kappa", d.ewald.kappa}, {"r_cut", d.ewald.r_cut}, {"n_max", d.ewald.n_max},
                         {"minimum_image_only", d.ewald.minimum_image_only}};
    if (d.ewald.minimum_image_only) summary_["warnings"].push_back("dipoles by a truncated minimum-image sum (smoke-test option, not for production)");
  }
}

void DmcRunner::run_preliminary(run::CheckpointClock& checkpoints) {
  const bool needed = protocol_.balance == BalanceMode::Equilibrium && protocol_.preliminary_cycles > 0 &&
                      (state_.species.size() > 1 || tracer_species_ >= 0);
  if (!needed) return;
  if (!summary_.contains("preliminary")) summary_["preliminary"] = nlohmann::json::array();
  Progress progress("dmc preliminary balance", protocol_.preliminary_cycles * protocol_.preliminary_iterations, quiet_);
  while (cursor_.preliminary_iteration < protocol_.preliminary_iterations) {
    while (cursor_.preliminary_cycle < protocol_.preliminary_cycles) {
      engine_.cycle();
      for (std::size_t s = 0; s < preliminary_totals_.size(); ++s) preliminary_totals_[s].add(engine_.last_cycle()[s]);
      ++cursor_.preliminary_cycle;
      progress.update(preliminary_cycles_done());
      checkpoints.tick(preliminary_cycles_done(), "preliminary cycle " + std::to_string(cursor_.preliminary_cycle));
    }
    const std::vector<double> next = balance_->balanced_steps(preliminary_totals_, dt_);
    double change = 0.0;
    for (std::size_t s = 0; s < next.size(); ++s) change = std::max(change, std::abs(next[s] / dt_[s] - 1.0));
    nlohmann::json it{{"cycles", protocol_.preliminary_cycles}, {"time_steps_before", dt_}, {"time_steps_after", next},
                      {"relative_change", change}, {"acceptance", nlohmann::json::array()}, {"overlap_pass", nlohmann::json::array()}};
    for (const auto& c : preliminary_totals_) {
      it["acceptance"].push_back(c.acceptance());
      it["overlap_pass"].push_back(c.pass_fraction());
    }
    summary_["preliminary"].push_back(it);
    dt_ = next;
    engine_.set_time_steps(dt_);
    ++cursor_.preliminary_iteration;
    cursor_.preliminary_cycle = 0;
    if (change < protocol_.preliminary_tolerance || cursor_.preliminary_iteration == protocol_.preliminary_iterations) break;
    std::fill(preliminary_totals_.begin(), preliminary_totals_.end(), TrialCounts{});
  }
  progress.finish();
}

std::int64_t DmcRunner::preliminary_cycles_done() const {
  return cursor_.preliminary_iteration * protocol_.preliminary_cycles + cursor_.preliminary_cycle;
}

void DmcRunner::run(io::H5mdWriter& out, std::int64_t checkpoint_every, const std::function<void()>& checkpoint) {
  // Checkpoint instants follow the cycle count (preliminary + production), so a resumed run keeps
  // the cadence of the original one.
  run::CheckpointClock checkpoints(checkpoint_every, checkpoint);
  if (!cursor_.production) {
    run_preliminary(checkpoints);
    // The smoothed acceptance estimates of few-particle species start from the preliminary run.
    balance_->seed(preliminary_totals_);
    // Displacements and rotations count from production's t = 0, which the summary's drift divides by.
    engine_.reset_accumulators();
    cursor_.production = true;
  }
  warn_about_tracer_validity();
  production_.run(out, checkpoints, preliminary_cycles_done());
  finish_summary();
}

void DmcRunner::warn_about_tracer_validity() {
  if (!engine_.tracer().active()) return;
  const double validity = engine_.tracer().beta_force * engine_.tracer_parallel_step();
  summary_["tracer_validity"] = validity;
  if (validity <= kTracerValidityLimit) return;
  const std::string w = "pulled tracer: βF·δx_par = " + std::to_string(validity) + " exceeds " +
                        std::to_string(kTracerValidityLimit) + "; the DMC time mapping needs βF·δx ≪ 1 (use a smaller time step)";
  if (std::find(summary_["warnings"].begin(), summary_["warnings"].end(), w) == summary_["warnings"].end())
    summary_["warnings"].push_back(w);
  std::fprintf(stderr, "anisodyn-dmc: warning: %s\n", w.c_str());
}

Vec3 DmcRunner::switch_field(bool on, std::int64_t step) {
  OrientationalField& field = engine_.orientational_field();
  if (on && field.active() && protocol_.field.check_direction) {
    // The field must be perpendicular to the nematic director (spec 10 §5): if it is not, turn it
    // into the plane perpendicular to the director and record the new direction.
    for (std::size_t s = 0; s < state_.species.size(); ++s) {
      if (!state_.species[s].shape.is_anisotropic()) continue;
      const auto order = body_axis_order(state_, static_cast<int>(s));
      int best = 0;
      for (int k = 1; k < 3; ++k) if (order[static_cast<std::size_t>(k)].order > order[static_cast<std::size_t>(best)].order) best = k;
      const Vec3 n = order[static_cast<std::size_t>(best)].director;
      if (order[static_cast<std::size_t>(best)].order > kNematicThreshold && std::abs(n.dot(field.direction)) > 0.1) {
        const Vec3 e = (field.direction - field.direction.dot(n) * n).normalized();
        summary_["warnings"].push_back("field direction turned perpendicular to the director of axis " + std::string(1, kAxisLetters[best]) +
                                       " at cycle " + std::to_string(step));
        field.direction = e;
      }
      break;
    }
  }
  engine_.set_field_on(on);
  return field.direction;
}

double DmcRunner::advance() {
  const std::vector<double> dt_used = dt_;
  cycle_.step(state_);  // its Brownian time comes from the balance below
  const auto& c = engine_.last_cycle();
  const double dt_bd = balance_->advance(c, dt_);
  if (protocol_.balance == BalanceMode::PerCycle) engine_.set_time_steps(dt_);
  for (std::size_t s = 0; s < c.size(); ++s) {
    production_totals_[s].add(c[s]);
    window_[s].add(c[s]);
  }
  // The realised balance uses the time steps in force during the cycle.
  balance_->add_to(window_balance_, c, dt_used);
  balance_->add_to(production_balance_, c, dt_used);
  return dt_bd;
}

void DmcRunner::after_step(io::H5mdWriter& out, std::int64_t step, double time) {
  if (!engine_.tracer().active() || step % protocol_.tracer->record_every != 0) return;
  run::record_tracer_position(out, state_, static_cast<std::size_t>(engine_.tracer().particle), step, time);
}

void DmcRunner::observe(io::H5mdWriter& out, std::int64_t step, double t) {
  const std::size_t ns = state_.species.size();
  std::vector<double> acc(ns), pass(ns);
  for (std::size_t s = 0; s < ns; ++s) {
    acc[s] = window_[s].acceptance();
    pass[s] = window_[s].pass_fraction();
  }
  const std::vector<double> balance = balance_->realised_balance(window_balance_);
  const bool orientational = protocol_.field.orientational.active(), dipolar = protocol_.field.dipoles.has_value();
  out.append_observable("acceptance", step, t, acc);
  out.append_observable("overlap_pass", step, t, pass);
  out.append_observable("time_step", step, t, dt_);
  out.append_observable("balance", step, t, balance);
  out.append_observable("field_on", step, t, engine_.field_on() ? 1.0 : 0.0);
  const double n = static_cast<double>(state_.particles.size());
  if (orientational) out.append_observable("field_energy", step, t, engine_.field_energy() / n);
  if (dipolar) out.append_observable("dipolar_energy", step, t, engine_.dipolar_energy() / n);
  for (std::size_t s = 0; s < ns; ++s) {
    if (!state_.species[s].shape.is_anisotropic()) continue;
    const auto o = body_axis_order(state_, static_cast<int>(s));
    out.append_observable("order_" + state_.species[s].name, step, t, std::vector<double>{o[0].order, o[1].order, o[2].order});
  }
  if (!attributes_written_) {
    auto attr = [&](const std::string& name, const std::string& units, const std::string& definition) {
      out.set_observable_attribute(name, "units", units);
      out.set_observable_attribute(name, "definition", definition);
    };
    attr("acceptance", "1", "acceptance per species (order of /parameters/species) over the cycles since the previous row");
    attr("overlap_pass", "1", "fraction of trials per species that passed the overlap test (the tracer's A_0)");
    attr("time_step", "tau", "MC time step δt_MC per species in force after the row's cycle");
    attr("balance", "1", "realised balance E_s δt_s / (E_ref δt_ref) per species over the cycles since the previous row, "
                         "E δt pooled as Σ(tried·E·δt)/Σ tried; NaN where the reference species had no trial or no positive E");
    attr("field_on", "1", "1 while the field is on, 0 while off");
    if (orientational) attr("field_energy", "kT", "orientational-field energy per particle βU/N");
    if (dipolar) attr("dipolar_energy", "kT", "dipolar (Ewald, tinfoil) energy per particle βU/N; 0 while the field is off");
    for (std::size_t s = 0; s < ns; ++s)
      if (state_.species[s].shape.is_anisotropic())
        attr("order_" + state_.species[s].name, "1", "uniaxial order parameters U_T, U_W, U_L (largest Q-tensor eigenvalue per body axis)");
    if (engine_.tracer().active()) run::describe_tracer_position(out);
    attributes_written_ = true;
  }
  std::fill(window_.begin(), window_.end(), TrialCounts{});
  window_balance_.clear(ns);
}

std::vector<io::ParticleElement> DmcRunner::frame_elements() const {
  return {{"body_displacement", 3, engine_.body_displacement().data()},
          {"body_rotation", 3, engine_.body_rotation().data()},
          {"rotation_vector", 9, engine_.rotation_vectors().data()}};
}

void DmcRunner::finish_summary() {
  const auto& ts = balance_->settings();
  summary_["cycles"] = production_.step();
  summary_["time"] = production_.time();
  summary_["switches"] = production_.switches();
  summary_["balance_mode"] = protocol_.balance == BalanceMode::PerCycle ? "per_cycle" : protocol_.balance == BalanceMode::None ? "none" : "equilibrium";
  summary_["reference"] = state_.species[static_cast<std::size_t>(ts.reference)].name;
  summary_["clock"] = state_.species[static_cast<std::size_t>(ts.clock)].name;
  summary_["rotation"] = protocol_.moves.rotation == RotationComposition::ExponentialMap ? "exponential" : "sequential";
  summary_["translation_frame"] = protocol_.moves.frame == TranslationFrame::Midpoint ? "midpoint" : "old";
  const auto realised = balance_->realised_balance(production_balance_);
  for (std::size_t s = 0; s < state_.species.size(); ++s) {
    auto& j = summary_["species"][s];
    j["name"] = state_.species[s].name;
    j["time_step"] = dt_[s];
    j["acceptance"] = production_totals_[s].acceptance();
    j["overlap_pass"] = production_totals_[s].pass_fraction();
    j["trials"] = production_totals_[s].tried;
    j["realised_balance"] = std::isnan(realised[s]) ? nlohmann::json(nullptr) : nlohmann::json(realised[s]);
  }
  if (engine_.tracer().active()) {
    const auto& t = engine_.tracer();
    const auto i = static_cast<std::size_t>(t.particle);
    const TrialCounts& c = production_totals_[static_cast<std::size_t>(tracer_species_)];
    nlohmann::json j{{"peclet", protocol_.tracer->peclet}, {"beta_force", t.beta_force}, {"parallel_step", engine_.tracer_parallel_step()},
                     {"acceptance", c.acceptance()}, {"overlap_pass", c.pass_fraction()},
                     {"a0", ts.a0 == TracerBathAcceptance::One ? nlohmann::json("one") : ts.a0 == TracerBathAcceptance::Fixed ? nlohmann::json(ts.a0_value) : nlohmann::json("overlap_pass")},
                     {"displacement_along_force", engine_.body_displacement()[3 * i + static_cast<std::size_t>(t.axis)]}};
    if (production_.time() > 0.0) j["drift_velocity"] = j["displacement_along_force"].get<double>() / production_.time();
    summary_["tracer"] = j;
  }
}

nlohmann::json DmcRunner::checkpoint_state() const {
  const DmcCursor& c = cursor_;
  return {{"cursor", {{"production", c.production}, {"preliminary_iteration", c.preliminary_iteration}, {"preliminary_cycle", c.preliminary_cycle}}},
          {"production", production_.checkpoint_state()},
          {"time_steps", dt_},
          {"engine", engine_.checkpoint()},
          {"balance", balance_->checkpoint()},
          {"preliminary_totals", counts_json(preliminary_totals_)},
          {"production_totals", counts_json(production_totals_)},
          {"window", counts_json(window_)},
          {"window_balance", window_balance_.to_json()},
          {"production_balance", production_balance_.to_json()},
          {"summary", summary_}};
}

void DmcRunner::restore(const nlohmann::json& j) {
  const auto& c = j.at("cursor");
  cursor_.production = c.at("production").get<bool>();
  cursor_.preliminary_iteration = c.at("preliminary_iteration").get<int>();
  cursor_.preliminary_cycle = c.at("preliminary_cycle").get<std::int64_t>();
  production_.restore(j.at("production"));
  dt_ = j.at("time_steps").get<std::vector<double>>();
  engine_.restore(j.at("engine"));
  balance_->restore(j.at("balance"));
  preliminary_totals_ = counts_from_json(j.at("preliminary_totals"));
  production_totals_ = counts_from_json(j.at("production_totals"));
  window_ = counts_from_json(j.at("window"));
  window_balance_.from_json(j.at("window_balance"));
  production_balance_.from_json(j.at("production_balance"));
  summary_ = j.at("summary");
}

}  // namespace anisodyn

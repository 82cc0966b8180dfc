#include "anisodyn/bd/bd_runner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "anisodyn/bd/slender_body.hpp"
#include "anisodyn/core/error.hpp"

namespace anisodyn {

namespace {
/// Order tensor S = ⟨ûû⟩ of the rods of species s: xx, yy, zz, xy, xz, yz.
std::vector<double> order_tensor(const State& st, int s) {
  Mat3 S = Mat3::Zero();
  std::size_t n = 0;
  for (std::size_t i = 0; i < st.particles.size(); ++i) {
    if (st.particles.species[i] != s) continue;
    const Vec3 u = st.particles.orientation(i) * Vec3::UnitZ();
    S += u * u.transpose();
    ++n;
  }
  if (n > 0) S /= static_cast<double>(n);
  return {S(0, 0), S(1, 1), S(2, 2), S(0, 1), S(0, 2), S(1, 2)};
}

/// Bins of x = d/D for P_d(x) (spec 20 §5: width 0.01 on [0, 1]).
constexpr std::size_t kDistanceBins = 100;

bool same(double a, double b) { return std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b)); }
}  // namespace

std::vector<BdDiffusion> bd_diffusion(const State& state, const std::string& file) {
  std::vector<BdDiffusion> out;
  for (const Species& sp : state.species) {
    const std::string at = "species." + sp.name;
    const Vec3& t = sp.D_trans;
    const Vec3& r = sp.D_rot;
    if (!(t.minCoeff() > 0.0))
      throw InputError(file, at + ".D_trans", "expected positive translational diffusion coefficients for species '" + sp.name +
                                                  "' (none in the input's species table): give them here or in the species file");
    if (!same(t.x(), t.y()))
      throw InputError(file, at + ".D_trans", "expected a body uniaxial about its L axis (D_trans T = W) for species '" + sp.name + "'");
    BdDiffusion d{t.z(), t.x(), 0.0};
    if (sp.shape.is_anisotropic()) {
      if (!(r.x() > 0.0) || !same(r.x(), r.y()))
        throw InputError(file, at + ".D_rot", "expected positive rotational diffusion of the L axis, equal about T and W, for species '" +
                                                  sp.name + "'");
      d.rotation = r.x();
    } else if (!same(t.x(), t.z())) {
      throw InputError(file, at + ".D_trans", "expected isotropic translational diffusion for the spheres of species '" + sp.name + "'");
    }
    out.push_back(d);
  }
  return out;
}

void apply_slender_body(State& state, const std::map<std::string, SlenderBodySpec>& slender_body, const BdUnits& units,
                        const std::string& file) {
  for (const auto& [name, spec] : slender_body) {
    const int index = species_index(state.species, name);
    if (index < 0) throw InputError(file, spec.path, "unknown species '" + name + "': expected one of the input's species");
    const auto it = state.species.begin() + index;
    if (it->shape.kind != ShapeKind::Spherocylinder)
      throw InputError(file, spec.path, "expected a rod (spherocylinder) species for the slender-body formulas; '" + name + "' is not");
    const double metres = units.si ? units.length_m : 1.0;
    const double diameter = spec.diameter.value_or(it->shape.diameter);
    if (!(it->shape.length > diameter))
      throw InputError(file, spec.path, "expected a rod longer than its diameter (L > D) for the slender-body formulas");
    const BdDiffusion d = slender_body_diffusion(it->shape.length * metres, diameter * metres, spec.viscosity, units.kT());
    const double to_units = 1.0 / (metres * metres);  // m²/s → length units²/s (SI); 1 reduced
    it->D_trans = Vec3(d.perpendicular, d.perpendicular, d.parallel) * to_units;
    it->D_rot = Vec3(d.rotation, d.rotation, 0.0);
  }
}

BdSettings BdRunner::integrator_settings(const std::string& config_file) const {
  BdSettings b;
  b.time_step = protocol_.time_step;
  b.kT = protocol_.units.kT();
  b.seed = protocol_.seed;
  b.replica = protocol_.replica;
  b.diffusion = bd_diffusion(state_, config_file);
  // Step bounds (spec 20 §4.5): no deterministic step longer than D/10 in translation or 2D/(10L)
  // in rotation, D the particle's diameter and L its length; the smallest bound over the species.
  double force = std::numeric_limits<double>::infinity(), torque = force;
  for (std::size_t s = 0; s < state_.species.size(); ++s) {
    const Shape& shape = state_.species[s].shape;
    const BdDiffusion& d = b.diffusion[s];
    force = std::min(force, 0.1 * shape.diameter * b.kT / (std::max(d.parallel, d.perpendicular) * b.time_step));
    if (d.rotation > 0.0) torque = std::min(torque, 0.2 * shape.diameter * b.kT / (shape.length * d.rotation * b.time_step));
  }
  auto cap = [](const BdCap& c, double bound) -> std::optional<double> {
    switch (c.kind) {
      case BdCap::Kind::None: return std::nullopt;
      case BdCap::Kind::Value: return c.value;
      case BdCap::Kind::StepBound: return std::isfinite(bound) ? std::optional<double>(bound) : std::nullopt;
    }
    return std::nullopt;
  };
  b.force_cap = cap(protocol_.force_cap, force);
  b.torque_cap = cap(protocol_.torque_cap, torque);
  return b;
}

BdRunner::BdRunner(State& state, const BdProtocol& protocol, const std::string& config_file, bool quiet)
    : state_(state), protocol_(protocol), production_(state, *this, run::production_settings(protocol, "bd"), quiet) {
  protocol_.diffusion.check(state_, config_file);
  protocol_.diffusion.apply(state_.species);
  apply_slender_body(state_, protocol_.slender_body, protocol_.units, config_file);
  const BdSettings settings = integrator_settings(config_file);
  build_rod_forces(config_file);
  build_sphere_forces(config_file);
  build_external_torque(config_file);
  build_tracer(config_file);
  ForceField forces;
  if (rod_forces_ || sphere_forces_ || external_ || tracer_) forces = [this](const State& s, BodyForces& out) { add_systematic_forces(s, out); };
  integrator_ = std::make_unique<BdIntegrator>(settings, forces);
  summary_["units"] = protocol_.units.to_json();
  summary_["species"] = nlohmann::json::array();
  for (std::size_t s = 0; s < state_.species.size(); ++s)
    summary_["species"].push_back({{"name", state_.species[s].name},
                                   {"D_parallel", settings.diffusion[s].parallel},
                                   {"D_perpendicular", settings.diffusion[s].perpendicular},
                                   {"D_rotation", settings.diffusion[s].rotation},
                                   {"slender_body", protocol_.slender_body.count(state_.species[s].name) > 0}});
  summary_["caps"] = {{"force", settings.force_cap ? nlohmann::json(*settings.force_cap) : nlohmann::json(nullptr)},
                      {"torque", settings.torque_cap ? nlohmann::json(*settings.torque_cap) : nlohmann::json(nullptr)}};
}

void BdRunner::build_rod_forces(const std::string& config_file) {
  if (!protocol_.potential) return;
  const OverlapVolumeSpec& spec = *protocol_.potential;
  int rods = -1;
  for (std::size_t s = 0; s < state_.species.size(); ++s) {
    const Species& sp = state_.species[s];
    const bool named = spec.species.empty() ? sp.shape.kind == ShapeKind::Spherocylinder : sp.name == spec.species;
    if (!named) continue;
    if (rods >= 0) throw InputError(config_file, spec.path + ".species", "expected the rod species to be named: the input has several rod species");
    rods = static_cast<int>(s);
  }
  if (rods < 0)
    throw InputError(config_file, spec.path + ".species",
                     spec.species.empty() ? "expected a rod (spherocylinder) species in the input" : "unknown species '" + spec.species + "'");
  const Shape& shape = state_.species[static_cast<std::size_t>(rods)].shape;
  if (shape.kind != ShapeKind::Spherocylinder || !(shape.length > shape.diameter))
    throw InputError(config_file, spec.path + ".species", "expected rods (spherocylinders) longer than their diameter");
  const double kT = protocol_.units.kT(), D = shape.diameter;
  OverlapVolumeSettings ov;
  ov.length = shape.length;
  ov.diameter = D;
  ov.hardness = spec.hardness ? *spec.hardness * kT / (D * D * D) : OverlapVolume::hardness_for(D, kT);
  ov.rule = spec.interior_only ? FiniteLengthRule::InteriorOnly : FiniteLengthRule::SegmentDistance;
  RodOverlapPairs pairs{OverlapVolume(ov), rods, {}, {}};
  const auto ns = static_cast<int>(state_.species.size());
  pair_distances_.assign(kDistanceBins, 0);
  rod_forces_ = std::make_unique<PairForceField<RodOverlapPairs>>(pairs, pairs.segment_cutoffs(ns), ns, spec.skin.value_or(shape.length / 20.0),
                                                                    pairs.half_lengths(ns));
  summary_["potential"] = {{"type", "overlap_volume"},
                           {"species", state_.species[static_cast<std::size_t>(rods)].name},
                           {"hardness", ov.hardness},
                           {"hardness_kT_per_D3", ov.hardness * D * D * D / kT},
                           {"finite_length", spec.interior_only ? "interior_only" : "segment_distance"}};
}

void BdRunner::build_sphere_forces(const std::string& config_file) {
  if (!protocol_.sphere_potential) return;
  const MieSpec& spec = *protocol_.sphere_potential;
  const double kT = protocol_.units.kT();
  MiePairs pairs;
  pairs.core = MieCore{spec.exponent, spec.exponent - 1.0, spec.epsilon_kT * kT};
  // σ of each species: its diameter, or the σ whose Barker–Henderson diameter is the diameter.
  const double bh = barker_henderson_ratio(pairs.core, kT);
  const double scale = spec.barker_henderson ? 1.0 / bh : 1.0;
  pairs.sigma.assign(state_.species.size(), 0.0);
  for (std::size_t k = 0; k < spec.species.size(); ++k) {
    const int s = species_index(state_.species, spec.species[k]);
    const std::string path = spec.path + ".species[" + std::to_string(k) + "]";
    if (s < 0) throw InputError(config_file, path, "unknown species '" + spec.species[k] + "'");
    if (state_.species[static_cast<std::size_t>(s)].shape.kind != ShapeKind::Sphere)
      throw InputError(config_file, path, "expected a sphere species: the Mie core acts between spheres");
  }
  nlohmann::json sigmas = nlohmann::json::object();
  double largest = 0.0;
  for (std::size_t s = 0; s < state_.species.size(); ++s) {
    const Species& sp = state_.species[s];
    const bool named = spec.species.empty() ? sp.shape.kind == ShapeKind::Sphere
                                            : std::find(spec.species.begin(), spec.species.end(), sp.name) != spec.species.end();
    if (!named) continue;
    pairs.sigma[s] = sp.shape.diameter * scale;
    sigmas[sp.name] = pairs.sigma[s];
    largest = std::max(largest, sp.shape.diameter);
  }
  if (largest == 0.0) throw InputError(config_file, spec.path + ".type", "expected sphere species in the input for the Mie potential");
  const auto ns = static_cast<int>(state_.species.size());
  const std::vector<double> cutoffs = pairs.cutoffs();
  sphere_forces_ = std::make_unique<PairForceField<MiePairs>>(std::move(pairs), cutoffs, ns, spec.skin.value_or(0.1 * largest));
  summary_["potential"] = {{"type", "mie"},
                           {"exponents", {spec.exponent, spec.exponent - 1.0}},
                           {"epsilon_kT", spec.epsilon_kT},
                           {"sigma", sigmas},
                           {"sigma_rule", spec.barker_henderson ? "barker_henderson" : "diameter"},
                           {"barker_henderson_diameter_over_sigma", bh}};
}

void BdRunner::build_tracer(const std::string& config_file) {
  if (!protocol_.tracer) return;
  const std::size_t i = run::find_pulled_tracer(*protocol_.tracer, state_, config_file);
  const double beta_force = run::pulled_tracer_beta_force(*protocol_.tracer, state_, i);
  tracer_ = i;
  tracer_force_ = beta_force * protocol_.units.kT() * Vec3::Unit(protocol_.tracer->axis);
  summary_["tracer"] = {{"species", protocol_.tracer->species}, {"pe", protocol_.tracer->peclet}, {"beta_force", beta_force},
                        {"axis", std::string(1, static_cast<char>('x' + protocol_.tracer->axis))}};
}

void BdRunner::add_systematic_forces(const State& s, BodyForces& out) {
  if (rod_forces_) (*rod_forces_)(s, out);
  if (sphere_forces_) (*sphere_forces_)(s, out);
  if (external_) add_external_torque(*external_, s, out);
  if (tracer_) out.force[*tracer_] += tracer_force_;
}

void BdRunner::sample_pair_distances() {
  const RodOverlapPairs& pairs = rod_forces_->evaluator();
  const double D = pairs.potential.settings().diameter;
  rod_forces_->for_each_pair(state_, [&](std::size_t i, std::size_t j, const Vec3& d) {
    if (!pairs.is_rod[i] || !pairs.is_rod[j]) return;
    const RodPairTerm t = pairs.potential(d, pairs.axes[i], pairs.axes[j]);
    if (!t.interacts) return;
    const auto bin = static_cast<std::size_t>(t.distance / D * static_cast<double>(kDistanceBins));
    ++pair_distances_[std::min(bin, kDistanceBins - 1)];
  });
  ++pair_distance_samples_;
}

void BdRunner::write_pair_distances(io::H5mdWriter& out) {
  // D_eff = D ∫x P_d dx / ∫P_d dx and σ_x from the bin centres (spec 20 §5).
  const double D = rod_forces_->evaluator().potential.settings().diameter;
  double n = 0, sx = 0, sxx = 0;
  std::vector<double> counts;
  for (std::size_t b = 0; b < kDistanceBins; ++b) {
    const double c = static_cast<double>(pair_distances_[b]), x = (static_cast<double>(b) + 0.5) / kDistanceBins;
    counts.push_back(c);
    n += c;
    sx += c * x;
    sxx += c * x * x;
  }
  out.append_observable("pair_distance_histogram", production_.step(), production_.time(), counts);
  out.set_observable_attribute("pair_distance_histogram", "units", "1");
  out.set_observable_attribute("pair_distance_histogram", "definition",
                               "counts of interacting rod pairs (V_ov > 0) by x = d/D, bins of 0.01 on [0, 1], d of the branch in use, "
                               "D the bare diameter, summed over every observation row of the run (spec 20 §5)");
  const double mean = n > 0 ? sx / n : std::nan(""), var = n > 0 ? sxx / n - mean * mean : std::nan("");
  summary_["pair_distances"] = {{"observations", pair_distance_samples_},
                                {"pairs", n},
                                {"mean_x", mean},
                                {"sigma_x", std::sqrt(std::max(0.0, var))},
                                {"effective_diameter", D * mean},
                                {"note", "x from the bin centres; D_eff = D <x>"}};
}

std::vector<io::ParticleElement> BdRunner::frame_elements() const {
  if (!rod_forces_) return {};
  frame_forces_.reset(state_.particles.size());
  (*rod_forces_)(state_, frame_forces_);
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 rows are stored contiguously");
  return {{"systematic_torque", 3, frame_forces_.torque.data()->data()}};
}

void BdRunner::build_external_torque(const std::string& config_file) {
  if (!protocol_.external_torque) return;
  const ExternalTorqueSpec& spec = *protocol_.external_torque;
  ExternalTorque ext;
  for (std::size_t k = 0; k < spec.particles.size(); ++k) {
    const auto& ids = state_.particles.id;
    const auto it = std::find(ids.begin(), ids.end(), spec.particles[k]);
    const std::string path = "external_torque.particles[" + std::to_string(k) + "]";
    if (it == ids.end()) throw InputError(config_file, path, "no particle with id " + std::to_string(spec.particles[k]) + " in the input");
    const auto i = static_cast<std::size_t>(it - ids.begin());
    if (!state_.species[static_cast<std::size_t>(state_.particles.species[i])].shape.is_anisotropic())
      throw InputError(config_file, path, "expected a rod: a sphere does not turn");
    ext.particles.push_back(i);
  }
  const double kT = protocol_.units.kT();
  ext.torque = spec.torque_kT * kT * spec.axis;
  ext.confinement = spec.confinement_kT * kT;
  external_ = ext;
  summary_["external_torque"] = {{"particles", spec.particles}, {"torque_kT", spec.torque_kT}, {"confinement_kT", spec.confinement_kT},
                                 {"axis", {spec.axis.x(), spec.axis.y(), spec.axis.z()}}};
}

void BdRunner::after_step(io::H5mdWriter& out, std::int64_t step, double time) {
  if (tracer_ && step % protocol_.tracer->record_every == 0) {
    run::record_tracer_position(out, state_, *tracer_, step, time);
    if (step == protocol_.tracer->record_every) run::describe_tracer_position(out);
  }
  if (!external_ || step % protocol_.external_torque->record_every != 0) return;
  std::vector<double> axes;
  for (const std::size_t i : external_->particles) {
    const Vec3 u = state_.particles.orientation(i) * Vec3::UnitZ();
    axes.insert(axes.end(), {u.x(), u.y(), u.z()});
  }
  out.append_observable("tagged_axes", step, time, axes);
  if (step == protocol_.external_torque->record_every) {
    out.set_observable_attribute("tagged_axes", "units", "1");
    out.set_observable_attribute("tagged_axes", "definition",
                                 "axes û (x, y, z) of the rods under the external torque, in the order of external_torque.particles");
  }
}

double BdRunner::advance() { return integrator_->step(state_); }

void BdRunner::observe(io::H5mdWriter& out, std::int64_t step, double t) {
  const double n = static_cast<double>(state_.particles.size());
  out.append_observable("potential_energy", step, t, integrator_->systematic().energy / n);
  out.append_observable("capped", step, t,
                        std::vector<double>{static_cast<double>(integrator_->capped_forces() - capped_forces_mark_),
                                            static_cast<double>(integrator_->capped_torques() - capped_torques_mark_)});
  capped_forces_mark_ = integrator_->capped_forces();
  capped_torques_mark_ = integrator_->capped_torques();
  for (std::size_t s = 0; s < state_.species.size(); ++s)
    if (state_.species[s].shape.is_anisotropic())
      out.append_observable("order_tensor_" + state_.species[s].name, step, t, order_tensor(state_, static_cast<int>(s)));
  if (rod_forces_) sample_pair_distances();
  if (attributes_written_) return;
  const std::string energy = protocol_.units.si ? "J" : "kT";
  auto attr = [&](const std::string& name, const std::string& units, const std::string& definition) {
    out.set_observable_attribute(name, "units", units);
    out.set_observable_attribute(name, "definition", definition);
  };
  attr("potential_energy", energy, "potential energy per particle at the start of the row's last step");
  attr("capped", "1", "particle-steps whose systematic force, and torque, was capped since the previous row");
  for (const auto& sp : state_.species)
    if (sp.shape.is_anisotropic())
      attr("order_tensor_" + sp.name, "1", "order tensor S = <u u> of the species' rod axes: xx, yy, zz, xy, xz, yz");
  attributes_written_ = true;
}

void BdRunner::run(io::H5mdWriter& out, std::int64_t checkpoint_every, const std::function<void()>& checkpoint) {
  run::CheckpointClock checkpoints(checkpoint_every, checkpoint);
  production_.run(out, checkpoints, 0);
  if (rod_forces_) write_pair_distances(out);
  finish_summary();
}

void BdRunner::finish_summary() {
  summary_["steps"] = production_.step();
  summary_["time"] = production_.time();
  summary_["time_step"] = protocol_.time_step;
  summary_["capped_forces"] = integrator_->capped_forces();
  summary_["capped_torques"] = integrator_->capped_torques();
}

nlohmann::json BdRunner::checkpoint_state() const {
  return {{"production", production_.checkpoint_state()},
          {"capped", {integrator_->capped_forces(), integrator_->capped_torques()}},
          {"capped_mark", {capped_forces_mark_, capped_torques_mark_}},
          {"pair_distances", pair_distances_},
          {"pair_distance_samples", pair_distance_samples_},
          {"summary", summary_}};
}

void BdRunner::restore(const nlohmann::json& j) {
  production_.restore(j.at("production"));
  integrator_->restore_counters(j.at("capped")[0].get<std::int64_t>(), j.at("capped")[1].get<std::int64_t>());
  capped_forces_mark_ = j.at("capped_mark")[0].get<std::int64_t>();
  capped_torques_mark_ = j.at("capped_mark")[1].get<std::int64_t>();
  pair_distances_ = j.at("pair_distances").get<std::vector<std::int64_t>>();
  pair_distance_samples_ = j.at("pair_distance_samples").get<std::int64_t>();
  summary_ = j.at("summary");
}

}  // namespace anisodyn

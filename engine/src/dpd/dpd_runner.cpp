#include "anisodyn/dpd/dpd_runner.hpp"

#include <cmath>

#include "anisodyn/core/error.hpp"
#include "anisodyn/core/keyed_random.hpp"
#include "anisodyn/core/ordered_sum.hpp"
#include "anisodyn/run/checkpoint_json.hpp"

namespace anisodyn {

namespace {

/// Purpose tags of the run's other keyed draws ("DPDSEED", "DPDVELO").
constexpr std::uint64_t kReplicaSeed = 0x44504453454544ULL;
constexpr std::uint64_t kStartVelocities = 0x44504456454c4fULL;

/// The key of replica K's draws: independent streams of one seed.
std::uint64_t replica_seed(std::uint64_t seed, std::uint64_t replica) { return KeyedRandom(seed, kReplicaSeed).block(replica, 0, 0, 0)[0]; }

std::vector<double> six(const Mat3& m) { return {m(0, 0), m(1, 1), m(2, 2), m(0, 1), m(0, 2), m(1, 2)}; }

}  // namespace

nlohmann::json DpdRowSums::to_json() const {
  return {{"steps", steps},
          {"kinetic_temperature", kinetic_temperature},
          {"potential_energy", potential_energy},
          {"colloid_translational", colloid_translational},
          {"total_energy", total_energy},
          {"wall_force", {run::vec3_json(wall_force[0]), run::vec3_json(wall_force[1])}},
          {"colloid_rotational", colloid_rotational},
          {"kinetic", run::mat3_json(kinetic)},
          {"virial", {run::mat3_json(virial[0]), run::mat3_json(virial[1]), run::mat3_json(virial[2])}}};
}

DpdRowSums DpdRowSums::from_json(const nlohmann::json& j) {
  DpdRowSums r;
  r.steps = j.at("steps").get<std::int64_t>();
  r.kinetic_temperature = j.at("kinetic_temperature").get<double>();
  r.potential_energy = j.at("potential_energy").get<double>();
  r.colloid_translational = j.at("colloid_translational").get<double>();
  r.total_energy = j.at("total_energy").get<double>();
  for (std::size_t w = 0; w < 2; ++w) r.wall_force[w] = run::vec3_from_json(j.at("wall_force")[w]);
  r.colloid_rotational = j.at("colloid_rotational").get<double>();
  r.kinetic = run::mat3_from_json(j.at("kinetic"));
  for (int k = 0; k < 3; ++k) r.virial[static_cast<std::size_t>(k)] = run::mat3_from_json(j.at("virial")[static_cast<std::size_t>(k)]);
  return r;
}

std::size_t DpdRunner::named_species(const std::string& name, const std::string& key, std::size_t k, const std::string& config_file) const {
  const int s = species_index(state_.species, name);
  if (s < 0)
    throw InputError(config_file, key + "[" + std::to_string(k) + "]", "unknown species '" + name + "': expected one of the input's species");
  return static_cast<std::size_t>(s);
}

std::vector<char> DpdRunner::liquid_species(const std::string& config_file) const {
  std::vector<char> liquid(state_.species.size(), protocol_.liquid_species.empty() ? 1 : 0);
  if (protocol_.colloids)
    for (std::size_t k = 0; k < protocol_.colloids->species.size(); ++k) {
      const std::string& name = protocol_.colloids->species[k];
      const std::size_t s = named_species(name, "colloids.species", k, config_file);
      if (protocol_.liquid_species.empty()) liquid[s] = 0;  // the liquid: every other species
    }
  for (std::size_t k = 0; k < protocol_.liquid_species.size(); ++k) {
    liquid[named_species(protocol_.liquid_species[k], "liquid.species", k, config_file)] = 1;
  }
  for (std::size_t s = 0; s < liquid.size(); ++s) {
    if (liquid[s] && state_.species[s].shape.is_anisotropic())
      throw InputError(config_file, "liquid.species", "expected point-like liquid particles (a sphere species); '" +
                                                          state_.species[s].name + "' is not a sphere (a colloid belongs in colloids.species)");
    if (!liquid[s] && !protocol_.colloids)
      throw InputError(config_file, "liquid.species", "species '" + state_.species[s].name +
                                                          "' is not liquid: expected every species in liquid.species, or the "
                                                          "others in colloids.species");
  }
  return liquid;
}

void DpdRunner::start_velocities() {
  Particles& p = state_.particles;
  if (protocol_.velocities == DpdProtocol::Velocities::Input ||
      (protocol_.velocities == DpdProtocol::Velocities::Default && p.has_velocities())) {
    summary_["start_velocities"] = "input";
    return;
  }
  // Maxwell–Boltzmann at kT, keyed by particle id (any particle order gives the same velocities),
  // then the mean momentum removed so that the liquid does not drift.
  p.carry_velocities();
  const KeyedRandom draw(replica_seed(protocol_.seed, protocol_.replica), kStartVelocities);
  Vec3 momentum = Vec3::Zero();
  double mass = 0.0;
  std::vector<char> at_rest(p.size(), 0);  // the colloids start at rest (spec 30 §5)
  if (colloids_)
    for (const std::int32_t c : colloids_->colloids()) at_rest[static_cast<std::size_t>(c)] = 1;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (at_rest[i]) {
      p.set_velocity(i, Vec3::Zero());
      continue;
    }
    double z[3];
    draw.normals(0, static_cast<std::uint64_t>(p.id[i]), 0, z, 3);
    const double m = state_.species[static_cast<std::size_t>(p.species[i])].mass;
    const Vec3 v = std::sqrt(protocol_.liquid.kT / m) * Vec3(z[0], z[1], z[2]);
    p.set_velocity(i, v);
    momentum += m * v;
    mass += m;
  }
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!at_rest[i]) p.set_velocity(i, p.velocity(i) - momentum / mass);
  summary_["start_velocities"] = "maxwell_boltzmann";
}

DpdRunner::DpdRunner(State& state, const DpdProtocol& protocol, const std::string& config_file, bool quiet)
    : state_(state), protocol_(protocol), production_(state, *this, run::production_settings(protocol, "dpd"), quiet) {
  const std::vector<char> liquid = liquid_species(config_file);
  const double reach = protocol_.liquid.cutoff + protocol_.skin;
  if (!(state_.box.edges().minCoeff() >= 2.0 * reach))
    throw InputError(config_file, "liquid.cutoff", "expected a box at least twice the cut-off plus the skin (" + std::to_string(2.0 * reach) +
                                                       ") along every edge, for the minimum image");
  for (const Species& sp : state_.species)
    if (!(sp.mass > 0.0)) throw InputError(config_file, "liquid.species", "expected a positive mass for species '" + sp.name + "'");
  for (const std::int64_t id : state_.particles.id)
    if (id < 0 || id > 0xFFFFFFFFLL)
      throw InputError(config_file, "liquid", "expected particle ids in 0 … 2^32 − 1 (the pair noise is keyed by them), got " + std::to_string(id));
  // Checked here, where an error still writes nothing; the velocities are drawn when a fresh run
  // starts (a resumed one has the checkpoint's).
  if (protocol_.velocities == DpdProtocol::Velocities::Input && !state_.particles.has_velocities())
    throw InputError(config_file, "velocities", "\"input\", but the input state has no velocities: use \"maxwell_boltzmann\"");

  const std::uint64_t seed = replica_seed(protocol_.seed, protocol_.replica);
  pairs_ = std::make_unique<DpdForceField>(protocol_.liquid, protocol_.time_step, seed, protocol_.skin);
  for (const Species& sp : state_.species) inertia_.push_back({sp.mass, Vec3::Zero()});  // point particles
  if (protocol_.colloids) {
    colloids_ = std::make_unique<ColloidCoupling>(state_, liquid, protocol_, seed, config_file);
    pairs_->set_liquid(colloids_->liquid());
    inertia_ = colloids_->inertia(state_.species);
    // The outputs' species table records the masses the run used (density matched, spec 30 §3).
    for (std::size_t s = 0; s < state_.species.size(); ++s) state_.species[s].mass = inertia_[s].mass;
  }
  if (colloids_) {
    liquid_ = colloids_->liquid();
  } else {
    liquid_.resize(state_.particles.size());
    for (std::size_t i = 0; i < liquid_.size(); ++i) liquid_[i] = static_cast<std::int32_t>(i);
  }
  if (protocol_.walls) {
    check_walls(config_file);
    walls_ = std::make_unique<FlatWalls>(*protocol_.walls, protocol_.time_step, seed);
  }
  check_core_time_step(config_file);
  if (protocol_.profiles && protocol_.profiles->radial_bin > 0.0 && !colloids_)
    throw InputError(config_file, "profiles.radial_bin", "expected colloids: the radial profiles are around the first colloid");
  if (protocol_.profiles) profiles_ = std::make_unique<FlowProfiles>(*protocol_.profiles);
  integrator_ = std::make_unique<RigidBodyNve>(protocol_.time_step, inertia_, [this](const State& s, BodyForces& out) { forces(s, out); });
  integrator_->set_velocity_prediction(protocol_.velocity_lambda);
  select_frame_particles(config_file);

  if (protocol_.green_kubo)
    green_kubo_ = std::make_unique<run::GreenKuboRecorder>(*protocol_.green_kubo, protocol_.time_step, run::run_steps(protocol_),
                                                           std::vector<std::string>{"kinetic", "conservative", "dissipative", "random"},
                                                           state_.box.volume(), protocol_.liquid.kT, config_file);

  const DpdParameters& d = protocol_.liquid;
  summary_["liquid"] = {{"a", d.a}, {"gamma", d.gamma}, {"kT", d.kT}, {"cutoff", d.cutoff}, {"skin", protocol_.skin},
                        {"noise_amplitude", std::sqrt(2.0 * d.gamma * d.kT)}};
  summary_["velocity_lambda"] = protocol_.velocity_lambda;
  summary_["particles"] = state_.particles.size();
  if (colloids_) {
    nlohmann::json bodies = nlohmann::json::object();
    for (std::size_t s = 0; s < state_.species.size(); ++s) {
      const ColloidBody& b = colloids_->bodies()[s];
      if (b.sites.size() == 0) continue;
      bodies[state_.species[s].name] = {{"sites", b.sites.size()}, {"mass", b.mass}, {"moment_perpendicular", b.moments.x()},
                                        {"volume", b.volume}, {"rotational_degrees", b.rotational_degrees}};
    }
    const auto& sh = protocol_.colloids->shell;
    summary_["colloids"] = {{"count", colloids_->colloids().size()}, {"liquid", colloids_->liquid().size()}, {"bodies", bodies},
                            {"gamma_surface", sh.gamma_surface}, {"shell", sh.shell},
                            {"shell_noise", sh.noise == SiteLiquidParameters::ShellNoise::Vector3d ? "vector3d" : "along_v"}};
  }
  summary_["density"] = static_cast<double>(state_.particles.size()) / state_.box.volume();
}

void DpdRunner::select_frame_particles(const std::string& config_file) {
  if (protocol_.frame_species.empty()) return;
  std::vector<char> shown(state_.species.size(), 0);
  for (std::size_t k = 0; k < protocol_.frame_species.size(); ++k) {
    shown[named_species(protocol_.frame_species[k], "frame_species", k, config_file)] = 1;
  }
  for (std::size_t i = 0; i < state_.particles.size(); ++i)
    if (shown[static_cast<std::size_t>(state_.particles.species[i])]) frame_particles_.push_back(i);
  if (frame_particles_.empty()) throw InputError(config_file, "frame_species", "expected species that have particles in the input");
}

const State& DpdRunner::frame_state(const State& full) {
  if (frame_particles_.empty()) return full;
  const Particles& p = full.particles;
  frame_subset_.box = full.box;
  frame_subset_.species = full.species;
  frame_subset_.step = full.step;
  frame_subset_.time = full.time;
  Particles& q = frame_subset_.particles;
  q = Particles{};
  if (p.has_velocities()) q.carry_velocities();
  if (p.has_angular_momenta()) q.carry_angular_momenta();
  for (const std::size_t i : frame_particles_) {
    q.add(p.species[i], p.position(i), p.orientation(i), p.id[i]);
    const std::size_t k = q.size() - 1;
    q.set_image(k, p.image(i));
    if (p.has_velocities()) q.set_velocity(k, p.velocity(i));
    if (p.has_angular_momenta()) q.set_angular_momentum(k, p.angular_momentum(i));
  }
  return frame_subset_;
}

void DpdRunner::forces(const State& s, BodyForces& out) {
  (*pairs_)(s, out);
  if (colloids_) (*colloids_)(s, out);
  if (walls_) walls_->add(s, liquid_, out);
  if (!protocol_.drives.empty()) {
    const double lz = s.box.edges().z();
    for (const std::int32_t index : liquid_) {
      const auto i = static_cast<std::size_t>(index);
      const double z = s.particles.z[i] - lz * std::floor(s.particles.z[i] / lz);  // in [0, L_z): between walls, z itself
      for (const DpdProtocol::Drive& drive : protocol_.drives)
        if (z >= drive.z_min && z < drive.z_max) out.force[i] += drive.force;
    }
  }
}

void DpdRunner::check_walls(const std::string& config_file) const {
  const FlatWallParameters& w = *protocol_.walls;
  const double lz = state_.box.edges().z();
  if (colloids_) throw InputError(config_file, "walls", "expected no colloids with walls (spec 30 has no colloid-wall interaction)");
  if (lz < w.height + protocol_.liquid.cutoff)
    throw InputError(config_file, "walls.height", "expected the box (" + std::to_string(lz) + " along z) to be taller than the channel by at "
                                                  "least the cut-off, so that no DPD pair reaches across the periodic boundary in z");
  // The liquid must start inside the channel: the walls' core is 1 kT at the planes and 2.6×10³ kT
  // 0.1 beyond them, so a particle of a running channel (a checkpoint) is never further out.
  constexpr double kPenetration = 0.1;
  for (const std::int32_t index : liquid_) {
    const auto i = static_cast<std::size_t>(index);
    const double z = state_.particles.z[i] + lz * state_.particles.iz[i];
    if (z < -kPenetration || z > w.height + kPenetration)
      throw InputError("", "", "liquid particle " + std::to_string(state_.particles.id[i]) + " is at z = " + std::to_string(z) +
                                   ", outside the channel 0 <= z <= " + std::to_string(w.height) + " between the walls (by more than 0.1)");
  }
}

void DpdRunner::check_core_time_step(const std::string& config_file) const {
  if ((!colloids_ && !walls_) || liquid_.empty()) return;
  double lightest = INFINITY;
  for (const std::int32_t i : liquid_) lightest = std::min(lightest, inertia_[static_cast<std::size_t>(state_.particles.species[static_cast<std::size_t>(i)])].mass);
  // ω = √(U''/m) at the core's surface (x = r − Δ = 1, the same for every d), U'' by a central
  // difference of the force. Velocity Verlet's linear limit is ω Δt < 2; ω Δt ≤ 1 keeps a margin for
  // the core's stiffening inside the surface.
  const ShiftedMieCore core;
  const double h = 1e-6;
  const double curvature = (core.force(1.0 - h, 2.0) - core.force(1.0 + h, 2.0)) / (2.0 * h);
  const double omega = std::sqrt(curvature / lightest);
  if (omega * protocol_.time_step > 1.0) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "expected a time step of at most %.6g for the Mie cores of the %s (surface frequency %.6g/tau for "
                  "the liquid mass %.6g; stability needs omega dt <= 1)", 1.0 / omega, colloids_ ? "colloids" : "walls", omega, lightest);
    throw InputError(config_file, "time_step", buf);
  }
}

void DpdRunner::set_noise_step(std::uint64_t step) {
  pairs_->set_noise_step(step);
  if (colloids_) colloids_->set_noise_step(step);
  if (walls_) walls_->set_noise_step(step);
}

double DpdRunner::advance() {
  set_noise_step(static_cast<std::uint64_t>(production_.step()) + 1);
  const double dt = integrator_->step(state_);
  add_to_row();
  return dt;
}

void DpdRunner::add_to_row() {
  const Particles& p = state_.particles;
  const Mat3 kinetic = ordered_sum(p.size(), Mat3::Zero().eval(), [&](std::size_t i) -> Mat3 {
    const Vec3 v = p.velocity(i);
    return inertia_[static_cast<std::size_t>(p.species[i])].mass * (v * v.transpose());
  });
  const double n = static_cast<double>(p.size());
  std::array<Mat3, 3> virial = pairs_->last_sums().virial;
  double energy = pairs_->last_sums().energy;
  double liquid_kinetic = kinetic.trace(), n_liquid = n, rotational = 0.0;
  if (colloids_) {
    const ColloidKinetics k = colloids_->kinetics(state_);
    rotational = k.rotational;
    liquid_kinetic -= k.translational;
    n_liquid = static_cast<double>(colloids_->liquid().size());
    row_.colloid_translational += k.translational;
    row_.colloid_rotational += k.rotational;
    energy += colloids_->last_sums().energy;
    for (std::size_t part = 0; part < 3; ++part) virial[part] += colloids_->last_sums().virial[part];
  }
  if (walls_)
    for (std::size_t w = 0; w < 2; ++w) row_.wall_force[w] += walls_->last_sums().force_on_wall[w];
  if (profiles_) profiles_->add(state_, liquid_, colloids_ ? state_.particles.position(static_cast<std::size_t>(colloids_->colloids().front())) : Vec3::Zero());
  row_.steps += 1;
  row_.kinetic += kinetic;
  row_.kinetic_temperature += liquid_kinetic / (3.0 * (n_liquid - 1.0));
  row_.potential_energy += energy / n;
  row_.total_energy += (0.5 * (kinetic.trace() + rotational) + energy) / n;
  for (std::size_t k = 0; k < 3; ++k) row_.virial[k] += virial[k];
  if (!green_kubo_) return;
  const double volume = state_.box.volume();
  green_kubo_->add(production_.step() + 1, {kinetic / volume, virial[0] / volume, virial[1] / volume, virial[2] / volume}, *out_);
}

void DpdRunner::observe(io::H5mdWriter& out, std::int64_t step, double t) {
  if (row_.steps == 0) return;
  const double steps = static_cast<double>(row_.steps), volume = state_.box.volume();
  const Mat3 kinetic = row_.kinetic / (steps * volume);
  std::array<Mat3, 3> parts;
  for (std::size_t k = 0; k < 3; ++k) parts[k] = row_.virial[k] / (steps * volume);
  const Mat3 total = kinetic + parts[0] + parts[1] + parts[2];
  out.append_observable("kinetic_temperature", step, t, row_.kinetic_temperature / steps);
  out.append_observable("pressure", step, t, total.trace() / 3.0);
  out.append_observable("pressure_tensor_kinetic", step, t, six(kinetic));
  out.append_observable("pressure_tensor_conservative", step, t, six(parts[0]));
  out.append_observable("pressure_tensor_dissipative", step, t, six(parts[1]));
  out.append_observable("pressure_tensor_random", step, t, six(parts[2]));
  out.append_observable("potential_energy", step, t, row_.potential_energy / steps);
  out.append_observable("total_energy", step, t, row_.total_energy / steps);
  if (colloids_) {
    const double n = static_cast<double>(colloids_->colloids().size());
    out.append_observable("colloid_temperature_translational", step, t, row_.colloid_translational / (3.0 * n * steps));
    if (const int f = colloids_->rotational_degrees(state_); f > 0)
      out.append_observable("colloid_temperature_rotational", step, t, row_.colloid_rotational / (f * steps));
  }
  if (walls_) {
    for (std::size_t w = 0; w < 2; ++w) {
      const Vec3 f = row_.wall_force[w] / steps;
      out.append_observable(w == 0 ? "wall_force_bottom" : "wall_force_top", step, t, std::vector<double>{f.x(), f.y(), f.z()});
    }
  }
  if (profiles_) profiles_->write(out, step, t, steps);
  Vec3 momentum = Vec3::Zero();
  const Particles& p = state_.particles;
  for (std::size_t i = 0; i < p.size(); ++i) momentum += inertia_[static_cast<std::size_t>(p.species[i])].mass * p.velocity(i);
  out.append_observable("momentum", step, t, std::vector<double>{momentum.x(), momentum.y(), momentum.z()});
  row_ = DpdRowSums{};
  if (attributes_written_) return;
  auto attr = [&](const std::string& name, const std::string& units, const std::string& definition) {
    out.set_observable_attribute(name, "units", units);
    out.set_observable_attribute(name, "definition", definition);
  };
  const std::string tensor = ": xx, yy, zz, xy, xz, yz, mean over the row's steps (velocities and forces of each step's end)";
  attr("kinetic_temperature", "kT", "sum of m v^2 / (3 (N - 1)) over the N liquid particles, full-step velocities, mean over the row's steps");
  if (colloids_) {
    attr("colloid_temperature_translational", "kT", "sum of M V^2 / (3 N_c) over the N_c colloids (centre-of-mass velocities), mean over the row's steps");
    if (colloids_->rotational_degrees(state_) > 0)
      attr("colloid_temperature_rotational", "kT", "sum of L . omega over the colloids / their rotational degrees of freedom (2 per rod, 3 per rotating sphere), mean over the row's steps");
  }
  attr("pressure", "kT/r_c^3", "trace/3 of the pressure tensor (the sum of the four parts), mean over the row's steps");
  attr("pressure_tensor_kinetic", "kT/r_c^3", "sum of m v v / V" + tensor);
  attr("pressure_tensor_conservative", "kT/r_c^3", "sum over pairs of r_ij F^C_ij / V" + tensor);
  attr("pressure_tensor_dissipative", "kT/r_c^3", "sum over pairs of r_ij F^D_ij / V (the velocities the forces see: half-step, or predicted with velocity_lambda)" + tensor);
  attr("pressure_tensor_random", "kT/r_c^3", "sum over pairs of r_ij F^R_ij / V" + tensor);
  attr("potential_energy", "kT", "potential energy per particle: sum of a r_c (1 - r/r_c)^2 / 2 over liquid pairs plus the colloid cores, mean over the row's steps");
  if (walls_) {
    attr("wall_force_bottom", "kT/r_c", "force of the liquid on the wall at z = 0 (x, y, z), mean over the row's steps");
    attr("wall_force_top", "kT/r_c", "force of the liquid on the wall at z = height (x, y, z), mean over the row's steps");
  }
  if (profiles_) profiles_->describe(out, state_.box);
  attr("total_energy", "kT", "(kinetic + rotational + potential energy) per particle, full-step velocities, mean over the row's steps; "
                             "conserved only without thermostat (gamma = 0, gamma_surface = 0)");
  attr("momentum", "m r_c/tau", "total momentum sum m v at the row's last step (x, y, z)");
  attributes_written_ = true;
}

void DpdRunner::start() {
  start_velocities();
  // Rotating colloids start at rest (spec 30 §5); carried from the start, so every frame has them.
  if (colloids_ && colloids_->rotational_degrees(state_) > 0 && !state_.particles.has_angular_momenta())
    state_.particles.carry_angular_momenta();
  // The starting forces, with the noise of step 0 (those after the drift of step n take n + 1).
  BodyForces forces;
  forces.reset(state_.particles.size());
  set_noise_step(0);
  this->forces(state_, forces);
  integrator_->restore_forces(std::move(forces));
}

void DpdRunner::run(io::H5mdWriter& out, std::int64_t checkpoint_every, const std::function<void()>& checkpoint) {
  if (!restored_) start();
  run::CheckpointClock checkpoints(checkpoint_every, checkpoint);
  out_ = &out;
  production_.run(out, checkpoints, 0);
  if (green_kubo_) green_kubo_->finish(production_.step(), out);
  out_ = nullptr;
  summary_["steps"] = production_.step();
  summary_["time"] = production_.time();
  summary_["time_step"] = protocol_.time_step;
}

nlohmann::json DpdRunner::checkpoint_state() const {
  return {{"production", production_.checkpoint_state()},
          {"row", row_.to_json()},
          {"profiles", profiles_ ? profiles_->to_json() : nlohmann::json()},
          {"forces", run::body_forces_json(integrator_->forces())},
          // The pair list's order decides the order of the force sums: rebuilt from these, it is the same.
          {"list_positions", pairs_->list_positions()},
          {"summary", summary_},
          {"green_kubo", green_kubo_ ? green_kubo_->to_json() : nlohmann::json()}};
}

void DpdRunner::restore(const nlohmann::json& j) {
  restored_ = true;
  production_.restore(j.at("production"));
  row_ = DpdRowSums::from_json(j.at("row"));
  if (profiles_) profiles_->restore(j.at("profiles"));
  integrator_->restore_forces(run::body_forces_from_json(j.at("forces")));
  const auto list_positions = j.at("list_positions").get<std::vector<double>>();
  if (!list_positions.empty()) pairs_->restore_list(state_.box, list_positions);  // none: colloids alone
  summary_ = j.at("summary");
  if (green_kubo_) green_kubo_->restore(j.at("green_kubo"));
}

}  // namespace anisodyn

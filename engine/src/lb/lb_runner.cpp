#include "anisodyn/lb/lb_runner.hpp"

#include <cmath>
#include <cstdio>

#include "anisodyn/core/error.hpp"
#include "anisodyn/core/keyed_random.hpp"
#include "anisodyn/run/checkpoint_json.hpp"
#include "anisodyn/system/rigid_sites.hpp"

namespace anisodyn::lb {

namespace {

/// Purpose tags of the run's keyed draws ("LBFLUID", "LBBEADS"): the fluid's and the beads' noise
/// are independent streams of one seed, per replica.
constexpr std::uint64_t kFluidSeed = 0x4c42464c554944ULL;
constexpr std::uint64_t kBeadSeed = 0x4c424245414453ULL;

std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t purpose, std::uint64_t replica) {
  return KeyedRandom(seed, purpose).block(replica, 0, 0, 0)[0];
}

/// The design surface of a species: a sphere's radius on every axis, or an ellipsoid's semi-axes
/// with b = c (a spheroid whose symmetry axis is body x, spec 40 §4).
Vec3 design_semi_axes(const Species& sp, const std::string& config_file) {
  if (sp.shape.kind == ShapeKind::Sphere) return Vec3::Constant(0.5 * sp.shape.diameter);
  if (sp.shape.kind == ShapeKind::Ellipsoid) {
    const Vec3 semi = sp.shape.half_extents();
    if (std::abs(semi.y() - semi.z()) > 1e-12 * semi.y())
      throw InputError(config_file, "raspberries.species", "expected spheroids with semi-axes (a, b, b), the symmetry axis along body x; '" +
                                                               sp.name + "' has b = " + std::to_string(semi.y()) + ", c = " + std::to_string(semi.z()));
    return semi;
  }
  throw InputError(config_file, "raspberries.species", "expected sphere or ellipsoid species (raspberries of spec 40 §5); '" + sp.name + "' is neither");
}

const char* layer_name(BeadLayer layer) {
  switch (layer) {
    case BeadLayer::kOuter: return "outer";
    case BeadLayer::kInner: return "inner";
    case BeadLayer::kFill: return "fill";
    case BeadLayer::kCentre: return "centre";
  }
  return "?";
}

}  // namespace

nlohmann::json LbRowSums::to_json() const {
  return {{"steps", steps},           {"force", run::vec3_json(force)},     {"torque", run::vec3_json(torque)},
          {"pore_force", run::vec3_json(pore_force)}, {"translational", translational}, {"rotational", rotational}};
}

LbRowSums LbRowSums::from_json(const nlohmann::json& j) {
  LbRowSums r;
  r.steps = j.at("steps").get<std::int64_t>();
  r.force = run::vec3_from_json(j.at("force"));
  r.torque = run::vec3_from_json(j.at("torque"));
  r.pore_force = run::vec3_from_json(j.at("pore_force"));
  r.translational = j.at("translational").get<double>();
  r.rotational = j.at("rotational").get<double>();
  return r;
}

std::vector<char> LbRunner::raspberry_species(const std::string& config_file) const {
  const auto& names = protocol_.raspberries.species;
  std::vector<char> raspberry(state_.species.size(), names.empty() ? 1 : 0);
  for (std::size_t k = 0; k < names.size(); ++k) {
    const int s = species_index(state_.species, names[k]);
    if (s < 0)
      throw InputError(config_file, "raspberries.species[" + std::to_string(k) + "]", "unknown species '" + names[k] + "': expected one of the input's species");
    raspberry[static_cast<std::size_t>(s)] = 1;
  }
  for (std::size_t i = 0; i < state_.particles.size(); ++i) {
    const auto s = static_cast<std::size_t>(state_.particles.species[i]);
    if (!raspberry[s])
      throw InputError(config_file, "raspberries.species", "species '" + state_.species[s].name + "' has particles in the input but is not a raspberry species: "
                                                           "expected every particle to be a raspberry");
  }
  return raspberry;
}

std::array<int, 3> LbRunner::lattice_dims(const std::string& config_file) const {
  std::array<int, 3> dims{};
  const Vec3 edges = state_.box.edges();
  for (int k = 0; k < 3; ++k) {
    const double nodes = edges[k] / units_.agrid;
    const double whole = std::round(nodes);
    if (whole < 1.0 || std::abs(nodes - whole) > 1e-9 * std::max(1.0, nodes)) {
      char buf[240];
      std::snprintf(buf, sizeof buf, "expected box edges that are whole multiples of the node spacing agrid = %g: the input's edge %c = %.10g is %.10g nodes",
                    units_.agrid, "xyz"[k], edges[k], nodes);
      throw InputError(config_file, "fluid.agrid", buf);
    }
    dims[static_cast<std::size_t>(k)] = static_cast<int>(whole);
  }
  return dims;
}

void LbRunner::build_bodies(const std::vector<char>& raspberry, const std::string& config_file) {
  const double density = protocol_.fluid.density;
  geometry_.resize(state_.species.size());
  for (std::size_t s = 0; s < state_.species.size(); ++s) {
    Species& sp = state_.species[s];
    if (!raspberry[s]) {
      inertia_.push_back({1.0, Vec3::Zero()});
      continue;
    }
    const Vec3 semi = design_semi_axes(sp, config_file);
    const double extent = 2.0 * semi.maxCoeff() + 2.0 * units_.agrid;
    if (state_.box.edges().minCoeff() < extent)
      throw InputError(config_file, "raspberries.species", "raspberry '" + sp.name + "' (largest extent " + std::to_string(2.0 * semi.maxCoeff()) +
                                                               ") is too large for the box: expected every edge at least its extent plus two node spacings (" +
                                                               std::to_string(extent) + ")");
    geometry_[s] = make_raspberry(semi, protocol_.raspberries.outer_layer);
    if (!protocol_.raspberries.centre_couples) {
      RaspberryGeometry& g = geometry_[s];
      for (std::size_t k = 0; k < g.offset.size(); ++k)
        if (g.layer[k] == BeadLayer::kCentre) {
          g.offset.erase(g.offset.begin() + static_cast<std::ptrdiff_t>(k));
          g.layer.erase(g.layer.begin() + static_cast<std::ptrdiff_t>(k));
          if (g.reference_bead > k) --g.reference_bead;
          break;
        }
    }
    BodyInertia inertia{raspberry_mass(semi, density), Vec3::Zero(), protocol_.raspberries.fixed};
    inertia.principal_moments = raspberry_moments(semi, inertia.mass);
    sp.mass = inertia.mass;  // the outputs' species table records the mass the run used (density matched)
    inertia_.push_back(inertia);
  }
  for (std::size_t i = 0; i < state_.particles.size(); ++i)
    if (state_.particles.id[i] < 0 || state_.particles.id[i] >= (std::int64_t{1} << (32 - BodyFluidCoupling::kBeadBits)))
      throw InputError(config_file, "raspberries", "expected particle ids in 0 … 2^20 − 1 (the bead noise is keyed by them), got " + std::to_string(state_.particles.id[i]));
}

void LbRunner::check_stability(const std::string& config_file) {
  const double xi = protocol_.raspberries.xi_bead * protocol_.raspberries.scaling.friction_scale();
  nlohmann::json bodies = nlohmann::json::object();
  for (std::size_t s = 0; s < state_.species.size(); ++s) {
    const RaspberryGeometry& g = geometry_[s];
    if (g.offset.empty()) continue;
    const double stability = protocol_.time_step * xi * static_cast<double>(g.offset.size()) / inertia_[s].mass;
    nlohmann::json counts = nlohmann::json::object();
    for (const BeadLayer layer : {BeadLayer::kOuter, BeadLayer::kInner, BeadLayer::kFill, BeadLayer::kCentre}) counts[layer_name(layer)] = g.count(layer);
    bodies[state_.species[s].name] = {{"semi_axes", run::vec3_json(g.semi_axes)}, {"beads", g.offset.size()}, {"layers", counts},
                                      {"mass", inertia_[s].mass}, {"principal_moments", run::vec3_json(inertia_[s].principal_moments)},
                                      {"reference_bead", g.reference_bead}, {"reference_offset", run::vec3_json(g.offset[g.reference_bead])},
                                      {"reference_angle", g.reference_angle}, {"stability", stability}};
    if (!quiet_)
      std::fprintf(stderr, "anisodyn-lb: raspberry '%s': %zu beads, mass %.6g; stability dt * sum(xi_bead) / m = %.4g (%s)\n", state_.species[s].name.c_str(),
                   g.offset.size(), inertia_[s].mass, stability, protocol_.raspberries.fixed ? "held fixed" : stability <= 0.5 ? "ok" : "above the advised 0.5");
    if (stability > 1.0 && !protocol_.raspberries.fixed && !protocol_.raspberries.allow_unstable) {
      char buf[300];
      std::snprintf(buf, sizeof buf, "expected dt * sum(xi_bead) / m <= 1 for stability (spec 40 §4); raspberry '%s' has %.4g (dt %g, %zu beads of "
                    "xi %.6g as simulated, mass %.6g): lower xi_bead or time_step, or set raspberries.allow_unstable", state_.species[s].name.c_str(),
                    stability, protocol_.time_step, g.offset.size(), xi, inertia_[s].mass);
      throw InputError(config_file, "raspberries.xi_bead", buf);
    }
  }
  summary_["raspberries"] = {{"bodies", bodies}, {"count", state_.particles.size()}, {"xi_bead", protocol_.raspberries.xi_bead},
                             {"xi_bead_simulated", xi}, {"centre_couples", protocol_.raspberries.centre_couples}, {"fixed", protocol_.raspberries.fixed},
                             {"layers", protocol_.raspberries.outer_layer ? "two" : "single"},
                             {"coupling_velocity", protocol_.raspberries.velocity == CouplingVelocity::kWithHalfForce ? "with_half_force" : "momentum_only"}};
}

void LbRunner::build_fluid(const std::array<int, 3>& dims) {
  const LbProtocol::Fluid& f = protocol_.fluid;
  LbParameters params;
  params.density = f.density * units_.agrid * units_.agrid * units_.agrid;
  params.viscosity = f.viscosity * units_.lb_time_step() / (units_.agrid * units_.agrid);
  params.bulk_relaxation = f.bulk_relaxation;
  params.ghost_relaxation = f.ghost_relaxation;
  params.kT = f.thermal ? protocol_.kT * units_.energy_to_lattice() : 0.0;
  params.seed = stream_seed(protocol_.seed, kFluidSeed, protocol_.replica);
  fluid_ = std::make_unique<LbFluid>(dims, params);
  // A force per volume: per node, times a³; in lattice units, over the lattice force unit.
  fluid_->set_body_force(f.body_force * units_.agrid * units_.agrid * units_.agrid / units_.force_from_lattice());
  const Vec3 u0 = units_.velocity_to_lattice() * f.initial_velocity;
  for (std::size_t n = 0; n < fluid_->nodes(); ++n) fluid_->set_equilibrium(n, params.density, u0);
  if (protocol_.walls) {
    const int normal = protocol_.walls->normal;
    const Vec3 wall = units_.velocity_to_lattice() * protocol_.walls->velocity;
    for (int z = 0; z < dims[2]; ++z)
      for (int y = 0; y < dims[1]; ++y)
        for (int x = 0; x < dims[0]; ++x)
          if (std::array<int, 3>{x, y, z}[static_cast<std::size_t>(normal)] == 0) fluid_->set_solid(fluid_->node(x, y, z), wall);
  }
  if (protocol_.pore) {
    // Nodes whose centre lies beyond R_pore from the axis are solid: with halfway bounce-back the
    // hydrodynamic wall is the staircase about R_pore (spec 40 §6).
    const Vec3 edges = state_.box.edges();
    for (int z = 0; z < dims[2]; ++z)
      for (int y = 0; y < dims[1]; ++y)
        for (int x = 0; x < dims[0]; ++x)
          if (std::hypot((x + 0.5) * units_.agrid - 0.5 * edges.x(), (y + 0.5) * units_.agrid - 0.5 * edges.y()) > protocol_.pore->radius)
            fluid_->set_solid(fluid_->node(x, y, z));
  }
  summary_["fluid"] = {{"nodes", {dims[0], dims[1], dims[2]}}, {"agrid", units_.agrid}, {"lb_steps", units_.lb_steps},
                       {"lb_time_step", units_.lb_time_step()}, {"density_lattice", params.density}, {"viscosity_lattice", params.viscosity},
                       {"tau", 3.0 * params.viscosity + 0.5}, {"kT_lattice", params.kT}, {"thermal", f.thermal},
                       {"shear_relaxation", params.shear_relaxation()}, {"warmup_steps", f.warmup_steps}};
}

void LbRunner::build_pore(const std::string& config_file) {
  const PoreParameters& pore = *protocol_.pore;
  const Vec3 edges = state_.box.edges();
  const double wall = pore.radius + pore.wall_bead_radius;
  if (0.5 * std::min(edges.x(), edges.y()) < wall)
    throw InputError(config_file, "pore.radius", "expected the wall beads (at R_pore + r_p = " + std::to_string(wall) + " from the axis) inside the box: "
                                                 "edges along x and y of at least " + std::to_string(2.0 * wall) + " (spec 40 §6: L_xy = 2(R_pore + r_p) + 2, rounded up)");
  SiteTable inner(state_.species.size());
  for (std::size_t s = 0; s < state_.species.size(); ++s) {
    const RaspberryGeometry& g = geometry_[s];
    for (std::size_t k = 0; k < g.offset.size(); ++k)
      if (g.layer[k] == BeadLayer::kInner) inner[s].offsets.push_back(g.offset[k]);
  }
  pore_ = std::make_unique<PoreWalls>(pore, state_.box, std::move(inner));
  if (edges.z() < 2.0 * std::pow(2.0, 1.0 / 6.0) * pore_->sigma())
    throw InputError(config_file, "pore.wall_bead_radius", "expected a box along the pore at least twice the wall's cut-off 2^(1/6) (r_r + r_p) = " +
                                                             std::to_string(std::pow(2.0, 1.0 / 6.0) * pore_->sigma()) + " long");
  for (std::size_t i = 0; i < state_.particles.size(); ++i) {
    const double reach = geometry_[static_cast<std::size_t>(state_.particles.species[i])].semi_axes.maxCoeff();
    const double d = pore_->radial_distance(state_.particles.position(i));
    if (d + reach > pore.radius)
      throw InputError(config_file, "pore.radius", "raspberry " + std::to_string(state_.particles.id[i]) + " (centre " + std::to_string(d) + " from the axis, reach " +
                                                   std::to_string(reach) + ") is not inside the pore of radius " + std::to_string(pore.radius));
  }
  summary_["pore"] = {{"radius", pore.radius}, {"wall_bead_radius", pore.wall_bead_radius}, {"rings", pore_->rings()},
                      {"ring_spacing", pore_->ring_spacing()}, {"beads_per_ring", pore_->beads_per_ring()}, {"sigma", pore_->sigma()}};
}

void LbRunner::forces(const State& s, BodyForces& out) {
  (*coupling_)(s, out);
  if (!pore_) return;
  pore_forces_.reset(s.particles.size());
  pore_->add(s, pore_forces_);
  last_pore_force_ = Vec3::Zero();
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    out.force[i] += pore_forces_.force[i];
    out.torque[i] += pore_forces_.torque[i];
    last_pore_force_ += pore_forces_.force[i];
  }
  out.energy += pore_forces_.energy;
}

LbRunner::LbRunner(State& state, const LbProtocol& protocol, const std::string& config_file, bool quiet)
    : state_(state), protocol_(protocol), quiet_(quiet), production_(state, *this, run::production_settings(protocol, "lb"), quiet) {
  units_ = LbUnits{protocol_.fluid.agrid, protocol_.time_step, protocol_.fluid.lb_steps};
  const std::array<int, 3> dims = lattice_dims(config_file);
  build_bodies(raspberry_species(config_file), config_file);
  check_stability(config_file);
  if (protocol_.walls) {
    // The walls are the planes at 0 and agrid along the normal (the solid layer of node 0): every
    // bead's stencil must stay in fluid nodes, between the centres of nodes 1 and n − 1.
    const int k = protocol_.walls->normal;
    const double length = state_.box.edges()[k];
    for (std::size_t i = 0; i < state_.particles.size(); ++i) {
      const double reach = geometry_[static_cast<std::size_t>(state_.particles.species[i])].semi_axes.maxCoeff();
      double c = state_.particles.position(i)[k];
      c -= length * std::floor(c / length);
      if (c - reach < 1.5 * units_.agrid || c + reach > length - 0.5 * units_.agrid)
        throw InputError(config_file, "walls.normal", "raspberry " + std::to_string(state_.particles.id[i]) + " (centre at " + "xyz"[k] + " = " + std::to_string(c) +
                                                          ", reach " + std::to_string(reach) + ") crosses the wall layer: expected it between " +
                                                          std::to_string(1.5 * units_.agrid) + " and " + std::to_string(length - 0.5 * units_.agrid));
    }
  }
  if (protocol_.pore) build_pore(config_file);
  build_fluid(dims);
  SiteTable sites(state_.species.size());
  std::vector<Vec3> moments;
  for (std::size_t s = 0; s < state_.species.size(); ++s) {
    sites[s].offsets = geometry_[s].offset;
    moments.push_back(inertia_[s].principal_moments);
  }
  const double kT = protocol_.fluid.thermal ? protocol_.kT : 0.0;
  const double xi = protocol_.raspberries.xi_bead * protocol_.raspberries.scaling.friction_scale();
  coupling_ = std::make_unique<BodyFluidCoupling>(*fluid_, std::move(sites), std::move(moments), xi, kT,
                                                  stream_seed(protocol_.seed, kBeadSeed, protocol_.replica), units_, protocol_.raspberries.velocity);
  integrator_ = std::make_unique<RigidBodyNve>(protocol_.time_step, inertia_, [this](const State& s, BodyForces& out) { forces(s, out); },
                                               [this](State& s, double dt) { coupling_->after_step(s, dt); });
  summary_["units"] = units_record(protocol_.raspberries.scaling, protocol_.fluid.density);
  summary_["kT"] = kT;
}

void LbRunner::start() {
  for (std::int64_t k = 0; k < protocol_.fluid.warmup_steps / units_.lb_steps; ++k) fluid_->step();
  Particles& p = state_.particles;
  if (!p.has_velocities() || protocol_.raspberries.fixed) {
    p.carry_velocities();
    for (std::size_t i = 0; i < p.size(); ++i) p.set_velocity(i, Vec3::Zero());
  }
  if (!p.has_angular_momenta() || protocol_.raspberries.fixed) {
    p.carry_angular_momenta();
    for (std::size_t i = 0; i < p.size(); ++i) p.set_angular_momentum(i, Vec3::Zero());
  }
  BodyForces start_forces;
  start_forces.reset(p.size());
  coupling_->set_noise_step(0);
  forces(state_, start_forces);
  integrator_->restore_forces(std::move(start_forces));
}

double LbRunner::advance() {
  coupling_->set_noise_step(static_cast<std::uint64_t>(production_.step()) + 1);
  const double dt = integrator_->step(state_);
  add_to_row();
  return dt;
}

void LbRunner::add_to_row() {
  const Particles& p = state_.particles;
  const BodyForces& f = integrator_->forces();
  row_.steps += 1;
  row_.pore_force += last_pore_force_;
  for (std::size_t i = 0; i < p.size(); ++i) {
    row_.force += f.force[i];
    row_.torque += f.torque[i];
    const BodyInertia& in = inertia_[static_cast<std::size_t>(p.species[i])];
    if (in.fixed) continue;
    row_.translational += in.mass * p.velocity(i).squaredNorm();
    row_.rotational += p.angular_momentum(i).dot(angular_velocity(p.orientation(i), p.angular_momentum(i), in.principal_moments));
  }
}

Vec3 LbRunner::fluid_momentum() const {
  return (fluid_->total_momentum() + fluid_->pending_force_total()) * (units_.agrid / units_.lb_time_step());
}

void LbRunner::observe(io::H5mdWriter& out, std::int64_t step, double t) {
  if (row_.steps == 0) return;
  const double steps = static_cast<double>(row_.steps);
  const Particles& p = state_.particles;
  out.append_observable("colloid_force", step, t, run::flatten({row_.force / steps}));
  out.append_observable("colloid_torque", step, t, run::flatten({row_.torque / steps}));
  if (pore_) out.append_observable("pore_force", step, t, run::flatten({row_.pore_force / steps}));
  if (!protocol_.raspberries.fixed && p.size() > 0) {
    const double n = static_cast<double>(p.size());
    out.append_observable("colloid_temperature_translational", step, t, row_.translational / (3.0 * n * steps));
    out.append_observable("colloid_temperature_rotational", step, t, row_.rotational / (3.0 * n * steps));
  }
  const auto [energy, nodes] = fluid_->kinetic_sum();
  out.append_observable("fluid_temperature", step, t, energy / (3.0 * static_cast<double>(nodes)) / units_.energy_to_lattice());
  const Vec3 fluid = fluid_momentum();
  Vec3 bodies = Vec3::Zero(), pending = Vec3::Zero();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const BodyInertia& in = inertia_[static_cast<std::size_t>(p.species[i])];
    if (in.fixed) continue;
    bodies += in.mass * p.velocity(i);
    pending += 0.5 * protocol_.time_step * integrator_->forces().force[i];
  }
  out.append_observable("fluid_momentum", step, t, run::flatten({fluid}));
  out.append_observable("colloid_momentum", step, t, run::flatten({bodies}));
  out.append_observable("total_momentum", step, t, run::flatten({fluid + bodies + pending}));
  row_ = LbRowSums{};
  if (!attributes_written_) describe_observables(out);
}

void LbRunner::describe_observables(io::H5mdWriter& out) {
  auto attr = [&](const std::string& name, const std::string& units, const std::string& definition) {
    out.set_observable_attribute(name, "units", units);
    out.set_observable_attribute(name, "definition", definition);
  };
  attr("colloid_force", "M0 sigma/t0^2", "sum over the raspberries of the force on them, the fluid coupling's and a pore wall's (x, y, z), mean over the row's MD steps (for fixed ones between walls: the drag)");
  if (pore_) attr("pore_force", "M0 sigma/t0^2", "sum over the raspberries of the pore wall beads' WCA force on their inner layers (x, y, z), mean over the row's MD steps");
  attr("colloid_torque", "M0 sigma^2/t0^2", "sum over the raspberries of the torque about their centres (x, y, z), mean over the row's MD steps");
  if (!protocol_.raspberries.fixed && state_.particles.size() > 0) {
    attr("colloid_temperature_translational", "kT", "sum of M V^2 / (3 N) over the N raspberries, full-step velocities, mean over the row's MD steps");
    attr("colloid_temperature_rotational", "kT", "sum of L . omega / (3 N) over the N raspberries, full-step, mean over the row's MD steps");
  }
  attr("fluid_temperature", "kT", "sum over fluid nodes of rho |u|^2 / (3 N_nodes), u = (j + f/2)/rho, at the row's last MD step");
  attr("fluid_momentum", "M0 sigma/t0", "sum of j over the nodes plus the force densities pending for the next LB step (x, y, z), at the row's last MD step");
  attr("colloid_momentum", "M0 sigma/t0", "sum of M V over the free raspberries (x, y, z), at the row's last MD step");
  attr("total_momentum", "M0 sigma/t0", "fluid_momentum + colloid_momentum + the half kick dt F/2 the bodies have still to take: constant for free "
                                        "raspberries without walls (it differs from the start's total by dt F_0 / 2)");
  attributes_written_ = true;
}

void LbRunner::run(io::H5mdWriter& out, std::int64_t checkpoint_every, const std::function<void()>& checkpoint) {
  if (!restored_) start();
  run::CheckpointClock checkpoints(checkpoint_every, checkpoint);
  production_.run(out, checkpoints, 0);
  summary_["steps"] = production_.step();
  summary_["time"] = production_.time();
  summary_["time_step"] = protocol_.time_step;
  summary_["lb_steps_taken"] = fluid_->steps();
}

nlohmann::json LbRunner::checkpoint_state() const {
  return {{"production", production_.checkpoint_state()},
          {"row", row_.to_json()},
          {"forces", run::body_forces_json(integrator_->forces())},
          {"fluid_steps", fluid_->steps()},
          {"summary", summary_}};
}

io::CheckpointArrays LbRunner::checkpoint_arrays() const {
  return {{"populations", fluid_->populations()}, {"pending_forces", fluid_->pending_forces()}};
}

void LbRunner::restore(const nlohmann::json& j) {
  restored_ = true;
  production_.restore(j.at("production"));
  row_ = LbRowSums::from_json(j.at("row"));
  integrator_->restore_forces(run::body_forces_from_json(j.at("forces")));
  restored_fluid_steps_ = j.at("fluid_steps").get<std::uint64_t>();  // with the populations (restore_arrays)
  summary_ = j.at("summary");
}

void LbRunner::restore_arrays(const std::function<std::vector<double>(const std::string&)>& read) {
  fluid_->restore(read("populations"), restored_fluid_steps_);
  fluid_->restore_pending_forces(read("pending_forces"));
}

}  // namespace anisodyn::lb

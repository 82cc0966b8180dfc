#pragma once
// An anisodyn-lb run (spec 40): raspberry bodies (lb/raspberry.hpp) in the fluctuating D3Q19 fluid
// (lb/lb_fluid.hpp), a client of the shared production runner whose step is one velocity-Verlet
// step of the rigid-body integrator (integrate/rigid_body_nve.hpp) with the bead coupling as its
// force field and the fluid's update as its hook (lb/body_fluid_coupling.hpp: Δt_LB = lb_steps Δt).
//
// Before the first MD step the fluid alone takes warmup_steps / lb_steps LB steps (spec 40 §2.4).
// The bead noise of the forces evaluated after the drift of MD step n is keyed by n + 1; the
// starting forces by 0. A checkpoint keeps the integrator's forces (they depend on the noise and
// the fluid) and, as arrays, the populations and the force densities pending for the next LB step,
// so a restart continues bit for bit.
//
// Observables, each the mean over the MD steps of its row unless said otherwise (docs/lb.md):
// the total force and torque on the raspberries (the coupling's and a pore's; for fixed ones
// between walls: the drag), the pore wall's force alone, their
// translational and rotational temperatures (free ones), and at the row's last step the fluid's
// temperature Σ ρ u²/(3 N_nodes), the momentum of the fluid (with the impulses pending for its
// next step), of the bodies, and their sum with the half kick the bodies have still to take.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/integrate/rigid_body_nve.hpp"
#include "anisodyn/io/h5md.hpp"
#include "anisodyn/lb/body_fluid_coupling.hpp"
#include "anisodyn/lb/lb_fluid.hpp"
#include "anisodyn/lb/lb_protocol.hpp"
#include "anisodyn/lb/pore_walls.hpp"
#include "anisodyn/lb/raspberry.hpp"
#include "anisodyn/run/production_runner.hpp"

namespace anisodyn::lb {

/// Per-step sums that an observation row averages.
struct LbRowSums {
  std::int64_t steps = 0;
  Vec3 force = Vec3::Zero(), torque = Vec3::Zero(), pore_force = Vec3::Zero();
  double translational = 0.0, rotational = 0.0;  // Σ M V², Σ L·ω

  nlohmann::json to_json() const;
  static LbRowSums from_json(const nlohmann::json& j);
};

class LbRunner : public run::FieldlessClient {
 public:
  LbRunner(State& state, const LbProtocol& protocol, const std::string& config_file, bool quiet);

  void run(io::H5mdWriter& out, std::int64_t checkpoint_every, const std::function<void()>& checkpoint);
  std::int64_t last_output_step() const { return production_.step(); }
  nlohmann::json checkpoint_state() const;
  /// The fluid's populations and pending force densities (too large for the JSON state).
  io::CheckpointArrays checkpoint_arrays() const;
  void restore(const nlohmann::json& j);
  void restore_arrays(const std::function<std::vector<double>(const std::string&)>& read);
  const nlohmann::json& summary() const { return summary_; }

 private:
  // run::ProductionClient
  double advance() override;
  void observe(io::H5mdWriter& out, std::int64_t step, double time) override;

  /// Which species are raspberries (raspberries.species, or every species).
  std::vector<char> raspberry_species(const std::string& config_file) const;
  /// The lattice's node counts: each box edge a whole number of node spacings.
  std::array<int, 3> lattice_dims(const std::string& config_file) const;
  /// Each raspberry species' bead geometry, mass and moments; checks that it fits the box.
  void build_bodies(const std::vector<char>& raspberry, const std::string& config_file);
  /// Δt Σ ξ_sim / m of each free species (spec 40 §4); refused above 1 unless allow_unstable.
  void check_stability(const std::string& config_file);
  void build_fluid(const std::array<int, 3>& dims);
  /// The pore's checks against the box and the bodies, and its wall beads (spec 40 §6).
  void build_pore(const std::string& config_file);
  /// The integrator's force field: the bead coupling, and the pore's wall.
  void forces(const State& s, BodyForces& out);
  /// A fresh run's start: the warm-up, the bodies' velocities (the input's, else at rest) and the
  /// first forces.
  void start();
  void add_to_row();
  void describe_observables(io::H5mdWriter& out);
  Vec3 fluid_momentum() const;

  State& state_;
  LbProtocol protocol_;
  bool quiet_;
  LbUnits units_;
  std::vector<RaspberryGeometry> geometry_;  // per species (empty offsets: not a raspberry)
  std::vector<BodyInertia> inertia_;         // per species
  std::unique_ptr<LbFluid> fluid_;
  std::unique_ptr<BodyFluidCoupling> coupling_;
  std::unique_ptr<PoreWalls> pore_;  // null: no pore
  BodyForces pore_forces_;           // the wall's part of the last forces
  Vec3 last_pore_force_ = Vec3::Zero();
  std::unique_ptr<RigidBodyNve> integrator_;
  run::ProductionRunner production_;
  LbRowSums row_;
  bool attributes_written_ = false;
  bool restored_ = false;
  std::uint64_t restored_fluid_steps_ = 0;
  nlohmann::json summary_ = nlohmann::json::object();
};

}  // namespace anisodyn::lb

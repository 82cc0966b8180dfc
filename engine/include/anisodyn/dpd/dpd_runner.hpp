#pragma once
// An anisodyn-dpd run (spec 30): a client of the shared production runner whose step is one
// velocity-Verlet step of the rigid-body integrator (integrate/rigid_body_nve.hpp) under the DPD
// pair forces (interactions/dpd_pairs.hpp). Liquid particles are point bodies (no rotation).
//
// The pair noise of the forces evaluated after the drift of step n is keyed by n + 1 (they belong
// to time t_{n+1}); the forces of the starting state, by 0. The forces depend on the half-step
// velocities and the noise, so a checkpoint keeps them: a restart continues bit for bit.
//
// Observables, each the mean over the steps of its row (docs/dpd.md): the kinetic temperature
// Σ m v²/(3(N − 1)) of the full-step velocities, the pressure tensor split into its kinetic,
// conservative, dissipative and random parts (each xx, yy, zz, xy, xz, yz), the pressure, the
// potential energy per particle; and the total momentum at the row's last step. With `green_kubo`,
// the four parts of every step's pressure tensor also go to the Green–Kubo record (run/green_kubo.hpp).
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/dpd/colloid_coupling.hpp"
#include "anisodyn/dpd/dpd_protocol.hpp"
#include "anisodyn/dpd/flow_profiles.hpp"
#include "anisodyn/integrate/rigid_body_nve.hpp"
#include "anisodyn/interactions/dpd_pairs.hpp"
#include "anisodyn/io/h5md.hpp"
#include "anisodyn/run/production_runner.hpp"
#include "anisodyn/run/time_step_run.hpp"

namespace anisodyn {

/// Per-step sums that an observation row averages.
struct DpdRowSums {
  std::int64_t steps = 0;
  double kinetic_temperature = 0.0, potential_energy = 0.0;
  double colloid_translational = 0.0, colloid_rotational = 0.0;  // Σ M V², Σ L·ω
  double total_energy = 0.0;  // per particle
  std::array<Vec3, 2> wall_force{Vec3::Zero(), Vec3::Zero()};  // Σ over steps of the liquid's force on each wall
  Mat3 kinetic = Mat3::Zero();                // Σ m v vᵀ
  std::array<Mat3, 3> virial{Mat3::Zero(), Mat3::Zero(), Mat3::Zero()};  // Σ r_ij F_ijᵀ by part

  nlohmann::json to_json() const;
  static DpdRowSums from_json(const nlohmann::json& j);
};

class DpdRunner : public run::FieldlessClient {
 public:
  DpdRunner(State& state, const DpdProtocol& protocol, const std::string& config_file, bool quiet);

  void run(io::H5mdWriter& out, std::int64_t checkpoint_every, const std::function<void()>& checkpoint);
  std::int64_t last_output_step() const { return production_.step(); }
  nlohmann::json checkpoint_state() const;
  void restore(const nlohmann::json& j);
  const nlohmann::json& summary() const { return summary_; }

 private:
  // run::ProductionClient
  double advance() override;
  void observe(io::H5mdWriter& out, std::int64_t step, double time) override;

  /// The index of species `name`, entry k of list `key` (InputError if the input has none of that name).
  std::size_t named_species(const std::string& name, const std::string& key, std::size_t k, const std::string& config_file) const;
  /// Which species are liquid (liquid.species, or every species that is not a colloid); without
  /// colloids every species must be.
  std::vector<char> liquid_species(const std::string& config_file) const;
  /// The state the frames show: every particle, or those of frame_species.
  const State& frame_state(const State& full) override;
  void select_frame_particles(const std::string& config_file);
  /// Walls and drive: their checks against the input state.
  void check_walls(const std::string& config_file) const;
  /// The Mie cores' (colloids', walls') limit on the time step.
  void check_core_time_step(const std::string& config_file) const;
  /// The DPD forces, the colloids' with the liquid, the walls' and the drive.
  void forces(const State& s, BodyForces& out);
  void set_noise_step(std::uint64_t step);
  /// A fresh run's start: the velocities (the input's, or Maxwell–Boltzmann) and the first forces.
  void start();
  void start_velocities();
  /// Adds the step's sums to the row (and to the Green–Kubo record).
  void add_to_row();

  State& state_;
  DpdProtocol protocol_;
  std::unique_ptr<DpdForceField> pairs_;
  std::unique_ptr<ColloidCoupling> colloids_;  // null: a pure liquid
  std::unique_ptr<FlatWalls> walls_;           // null: periodic in z
  std::unique_ptr<FlowProfiles> profiles_;     // null: none
  std::vector<std::int32_t> liquid_;           // the liquid particles' indices
  std::vector<BodyInertia> inertia_;           // per species
  std::vector<std::size_t> frame_particles_;   // empty: every particle
  State frame_subset_;
  std::unique_ptr<RigidBodyNve> integrator_;
  run::ProductionRunner production_;
  std::unique_ptr<run::GreenKuboRecorder> green_kubo_;
  io::H5mdWriter* out_ = nullptr;  // during run(): where the Green–Kubo rows go
  DpdRowSums row_;
  bool attributes_written_ = false;
  bool restored_ = false;
  nlohmann::json summary_ = nlohmann::json::object();
};

}  // namespace anisodyn

#pragma once
// An anisodyn-bd run: production by the shared production runner (run/production_runner.hpp), of
// which BD is a client: one step is one BdIntegrator step of Δt. Observables every observe_every
// steps: the order tensor of each rotating species, the capped force and torque events since the
// previous row, the potential energy per particle; with the rod potential, the histogram P_d(x) of
// x = d/D over the interacting rod pairs at every observation (spec 20 §5), written at the end with
// the effective diameter. Checkpoints continue bit for bit.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/bd/bd_integrator.hpp"
#include "anisodyn/bd/external_torque.hpp"
#include "anisodyn/bd/bd_protocol.hpp"
#include "anisodyn/interactions/mie_pairs.hpp"
#include "anisodyn/interactions/pair_force_field.hpp"
#include "anisodyn/interactions/rod_overlap_pairs.hpp"
#include "anisodyn/io/h5md.hpp"
#include "anisodyn/run/production_runner.hpp"
#include "anisodyn/run/time_step_run.hpp"

namespace anisodyn {

/// The body-frame diffusion of each species for BD: uniaxial about body z (the rod axis L), so
/// D_trans T = W is D_⊥, L is D_∥, and D_rot T = W turns the axis; spheres translate only.
/// Throws InputError(file, "species.<name>…") for a species the dynamics cannot move.
std::vector<BdDiffusion> bd_diffusion(const State& state, const std::string& file);

/// Sets the D tensors of the species named in `slender_body` from the slender-body formulas, in
/// the run's units (SI: lengths converted to metres and D back to length units²/s). Throws
/// InputError(file, "slender_body.<name>") for an unknown species or one that is not a rod.
void apply_slender_body(State& state, const std::map<std::string, SlenderBodySpec>& slender_body, const BdUnits& units,
                        const std::string& file);

class BdRunner : public run::FieldlessClient {
 public:
  BdRunner(State& state, const BdProtocol& protocol, const std::string& config_file, bool quiet);

  void run(io::H5mdWriter& out, std::int64_t checkpoint_every, const std::function<void()>& checkpoint);
  std::int64_t last_output_step() const { return production_.step(); }
  nlohmann::json checkpoint_state() const;
  void restore(const nlohmann::json& j);
  const nlohmann::json& summary() const { return summary_; }

 private:
  // run::ProductionClient
  double advance() override;
  void observe(io::H5mdWriter& out, std::int64_t step, double time) override;
  /// With the rod potential: the systematic torque on each particle at the frame's configuration,
  /// before any cap (spec 20 §6.3, Method III's T̄), as `systematic_torque`.
  std::vector<io::ParticleElement> frame_elements() const override;
  /// Method II: the axes of the tagged rods every record_every steps; the pulled tracer's position.
  void after_step(io::H5mdWriter& out, std::int64_t step, double time) override;

  BdSettings integrator_settings(const std::string& config_file) const;
  /// The rod–rod force field of protocol_.potential, or none.
  void build_rod_forces(const std::string& config_file);
  /// The sphere–sphere Mie cores of protocol_.sphere_potential, or none.
  void build_sphere_forces(const std::string& config_file);
  void build_external_torque(const std::string& config_file);
  void build_tracer(const std::string& config_file);
  /// Every systematic force and torque of the state (potentials, external torque, tracer force).
  void add_systematic_forces(const State& s, BodyForces& out);
  void finish_summary();
  /// Adds the interacting rod pairs of the current state to the P_d(x) histogram.
  void sample_pair_distances();
  void write_pair_distances(io::H5mdWriter& out);

  State& state_;
  BdProtocol protocol_;
  std::unique_ptr<PairForceField<RodOverlapPairs>> rod_forces_;
  std::unique_ptr<PairForceField<MiePairs>> sphere_forces_;
  std::unique_ptr<BdIntegrator> integrator_;
  mutable BodyForces frame_forces_;
  std::optional<ExternalTorque> external_;
  std::optional<std::size_t> tracer_;  // the pulled tracer's particle
  Vec3 tracer_force_ = Vec3::Zero();
  run::ProductionRunner production_;
  std::int64_t capped_forces_mark_ = 0, capped_torques_mark_ = 0;
  bool attributes_written_ = false;
  std::vector<std::int64_t> pair_distances_;  // P_d(x): counts in bins of x = d/D of width 0.01
  std::int64_t pair_distance_samples_ = 0;    // observations that added to it
  nlohmann::json summary_ = nlohmann::json::object();
};

}  // namespace anisodyn

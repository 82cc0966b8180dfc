#pragma once
// Active (constant-force) microrheology of a pulled tracer (spec 50 §6.3–6.4):
//   - effective friction (F3): γ_eff/γ_0 = D_s βF / ⟨v⟩. Over the steady part of each replica
//     (Decision: from the first time the tracer has moved 2σ along ê, or from the configured
//     `steady_from`) the tracer's displacement along ê is a drifting random walk, whose maximum-
//     likelihood drift is the end-to-end displacement over the elapsed time (a least-squares slope
//     of the whole path weights the noisy ends and has a larger variance). ⟨v⟩ pools the replicas
//     the same way, Σ Δz_i / Σ Δt_i; the errors are jackknifes over replicas (over 10 consecutive
//     time blocks of the steady part for a single replica), reported with the plain scatter of the
//     per-replica velocities. At Pe = 0 the velocity is measured (it should vanish), γ_eff/γ_0 is
//     undefined (NaN) and the steady part is the whole run unless `steady_from` says otherwise;
//   - axisymmetric density map (F4) of the bath around the tracer: Δz = (r_j − r_t)·ê (minimum image,
//     +Δz upstream), ρ_c the distance from the line through the tracer along ê, bins 0.25 × 0.25
//     (Decision), ring volume π[(ρ_c + Δρ)² − ρ_c²]Δz, normalised by ρ_bath = N_c/V, averaged over
//     the steady frames and the replicas; the local uniaxial order U of one body axis per bin; the
//     on-axis profile ρ(Δz, ρ_c < 0.5σ) and the wake length, the distance behind the tracer at which
//     the on-axis density first recovers to 0.9 ρ_bath (Decision).
//
// Use: ActiveMicrorheology a(settings, replicas); a.accumulate(trajectory) per replica;
// ActiveResult r = a.compute().
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/analysis/replica_statistics.hpp"
#include "anisodyn/analysis/trajectory.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::analysis {

enum class TracerPathSource { Auto, Frames, Observable };

struct ActiveMicrorheologySettings {
  std::string species;                  // the pulled tracer (required; exactly one particle)
  std::string bath_species;             // "" = every particle not of the tracer species
  double beta_force = std::numeric_limits<double>::quiet_NaN();  // βF [1/length]
  double D_s = std::numeric_limits<double>::quiet_NaN();         // free translational D of the tracer
  double peclet = std::numeric_limits<double>::quiet_NaN();      // βF = Pe / a when βF is not given
  double radius = std::numeric_limits<double>::quiet_NaN();      // tracer radius a, for Pe only
  Vec3 direction = Vec3::UnitZ();       // force direction, along a box axis
  bool direction_given = false;         // else the run's tracer.axis (if any), else +z
  double steady_distance = 2.0;         // Decision: the steady part starts after moving 2σ along ê (βF > 0 only)
  bool steady_distance_given = false;
  std::optional<double> steady_from;    // or from this mapped time
  TracerPathSource source = TracerPathSource::Auto;
  bool density_map = true;
  double dz_bin = 0.25, rho_bin = 0.25;  // Decision
  double on_axis_radius = 0.5;           // ρ_c < 0.5σ
  double wake_threshold = 0.9;           // Decision: recovery to 0.9 ρ_bath
  int order_axis = 2;                    // body axis for U (0 T, 1 W, 2 L); −1 = none
  std::size_t single_replica_blocks = 10;
};

/// Reads the keys of the active mode: species, bath_species, beta_force | force (+ kT) | pe (+ radius |
/// tracer_diameter), D_s, direction, steady_distance, steady_from, position_source, density_map,
/// bin_width (or dz_bin, rho_bin), on_axis_radius, wake_threshold, order_axis. A force of 0 (Pe = 0)
/// is valid: the run is then a passive reference.
ActiveMicrorheologySettings parse_active_microrheology_settings(tool::ConfigNode& cfg);

/// Fills the defaults that live in the trajectory: βF from `pe` (or the run's tracer.pe) and the
/// tracer radius (its sphere diameter / 2), D_s from the species table (sphere with isotropic D).
/// Records in `details` where each value came from. InputError naming config_file and the key if a
/// value cannot be found.
void resolve_active_defaults(ActiveMicrorheologySettings& s, const SpeciesTable& table, const nlohmann::json& run_parameters,
                             const std::string& config_file, nlohmann::json& details);

/// The steady-state velocity of one path s(t) = (r(t) − r(t_0))·ê over the points with t ≥ t_start
/// (t_start = steady_from, or the first time s ≥ steady_distance): the end-to-end drift
/// [s(t_end) − s(t_start)] / (t_end − t_start), with the error √(σ²/(t_end − t_start)) of a Brownian drift
/// whose σ² = Σ (Δs_k − v Δt_k)² / Δt_total · n/(n − 1) comes from the path's own increments.
struct SteadyVelocity {
  double velocity = std::numeric_limits<double>::quiet_NaN(), velocity_error = std::numeric_limits<double>::quiet_NaN();
  double t_start = std::numeric_limits<double>::quiet_NaN(), t_end = std::numeric_limits<double>::quiet_NaN();
  double displacement = std::numeric_limits<double>::quiet_NaN();  // s(t_end) − s(t_start)
  std::size_t points = 0, first = 0;  // points in the steady part, index of the first one
  double duration() const { return t_end - t_start; }
};
SteadyVelocity steady_velocity(const std::vector<double>& time, const std::vector<double>& displacement,
                               double steady_distance, std::optional<double> steady_from);

struct DensityMapGrid {
  std::size_t nz = 0, nrho = 0;
  double dz = 0.25, drho = 0.25, z_min = 0;  // bin (k, m) covers [z_min + k dz, +dz) × [m drho, +drho)
  double dz_centre(std::size_t k) const { return z_min + (static_cast<double>(k) + 0.5) * dz; }
  double rho_centre(std::size_t m) const { return (static_cast<double>(m) + 0.5) * drho; }
  double ring_volume(std::size_t m) const;
};

struct ActiveResult {
  // friction, per replica
  std::vector<SteadyVelocity> replicas;
  std::vector<std::string> replica_paths;
  std::string path_source;          // "frames" or "observable tracer_position"
  Estimate velocity;                // Σ Δz / Σ Δt over replicas (or blocks), jackknife error
  Estimate gamma_ratio;             // D_s βF / ⟨v⟩, jackknife; NaN at βF = 0
  Estimate replica_velocity;        // plain mean ± SE of the per-sample velocities (the scatter, for comparison)
  double velocity_scatter = std::numeric_limits<double>::quiet_NaN();  // their standard deviation
  std::size_t velocity_samples = 0;
  double beta_force = 0, D_s = 0;
  // density map
  bool has_map = false, has_order = false;
  DensityMapGrid grid;
  std::vector<double> density, density_error, order, particle_frames;  // [nz × nrho], index k·nrho + m
  std::vector<double> on_axis, on_axis_error;                          // [nz]
  double on_axis_radius_used = 0;
  Estimate wake_length;
  std::size_t map_samples = 0, steady_frames = 0, bath_particles = 0;
};

class ActiveMicrorheology {
 public:
  ActiveMicrorheology(ActiveMicrorheologySettings settings, std::size_t replicas, std::string config_file = "");
  /// Adds one replica; the tracer species must exist with exactly one particle, the path must reach the
  /// steady part with ≥ 3 points, and (with the map) ≥ 1 steady frame — InputError otherwise.
  void accumulate(const Trajectory& t);
  ActiveResult compute() const;

 private:
  struct PathSeries { std::vector<double> time, displacement; };
  PathSeries tracer_path(const Trajectory& t, std::size_t tracer);
  void add_velocity_samples(const PathSeries& p, const SteadyVelocity& v);
  void add_map(const Trajectory& t, std::size_t tracer, double t_start);
  void setup_map(const Trajectory& t, const std::vector<std::size_t>& bath);
  /// Adds one frame's bath counts / (ring volume · N_c/V) to `map`, and the order sums.
  void add_frame(const Trajectory& t, std::size_t f, std::size_t tracer, const std::vector<std::size_t>& bath, std::vector<double>& map);
  /// Closes one sample (replica or block) of `frames` frames: map statistics and on-axis profile.
  void add_map_sample(std::vector<double> map, double frames);
  std::vector<std::size_t> bath_members(const Trajectory& t, int tracer_species) const;

  ActiveMicrorheologySettings s_;
  std::size_t replicas_;
  std::string config_file_;
  int axis_ = 2;          // box axis of the force
  double sign_ = 1.0;     // +1 or −1 along that axis
  // friction
  std::vector<SteadyVelocity> per_replica_;
  std::vector<std::string> paths_;
  std::string source_used_;
  CurveSamples velocity_samples_;
  // map
  DensityMapGrid grid_;
  std::vector<double> sum_, sum_sq_;           // Σ over samples of the per-sample density map, and of its square
  std::vector<double> order_sum_;              // pooled Σ u_a u_b (6 per bin)
  std::vector<double> pooled_count_;           // pooled particle-frames per bin
  CurveSamples on_axis_samples_;
  std::size_t map_samples_ = 0, steady_frames_ = 0, bath_ = 0;
  bool has_order_ = false;
  double on_axis_radius_used_ = 0;
  std::size_t on_axis_bins_ = 1;               // ρ bins inside the on-axis cylinder
};

}  // namespace anisodyn::analysis

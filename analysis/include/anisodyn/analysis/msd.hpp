#pragma once
// Translational displacement statistics (spec 50 §1): MSD per component (total, x, y, z, parallel
// and perpendicular to a reference direction, body-frame cumulative components), the non-Gaussian
// parameter, the apparent exponent β(t) and long-time diffusion coefficients from a linear fit.
//
// Use (freud style): MsdAnalysis msd(settings, replica_count); msd.accumulate(trajectory) for each
// replica; MsdResult r = msd.compute(). Averages run over the species' particles, every time
// origin of each lag class (lag_grid.hpp) and the replicas; errors are the standard error over
// replicas, or over 10 blocks of time origins when there is a single replica.
#include <optional>
#include <string>
#include <vector>

#include "anisodyn/analysis/lag_grid.hpp"
#include "anisodyn/analysis/replica_statistics.hpp"
#include "anisodyn/analysis/trajectory.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::analysis {

enum class MsdReference { Axes, Director, Vector, ParticleAxis };

struct MsdSettings {
  std::string species;                 // "" = every species separately (chosen by the caller)
  MsdReference reference = MsdReference::Axes;
  int axis = -1;                       // body axis for director / particle_axis (0 T, 1 W, 2 L); −1 = largest U
  std::string director_species;        // director reference of spheres: the species whose director they use
                                       // ("" = the only anisotropic species of the file)
  Vec3 direction = Vec3::UnitZ();      // for MsdReference::Vector (a field direction)
  double lags_per_decade = 10.0;
  std::size_t max_origins = 0;         // 0 = every origin
  bool body_frame = false;             // body-frame cumulative displacement components
  std::optional<std::pair<double, double>> fit_window;  // absent = automatic (spec 50 §1.3)
  std::string ngp_constant = "auto";   // isotropic | anisotropic | auto (anisotropic with a director)
  double beta_half_width = 0.1;        // decades, smoothing of β(t)
  std::size_t single_replica_blocks = 10;
  double director_threshold = 0.40;    // a director needs a largest U above this (spec 50 §3.1)
};

/// Reads the MSD keys of a stage configuration (see docs/analysis.md).
MsdSettings parse_msd_settings(tool::ConfigNode& cfg);

struct MsdComponent {
  std::string name;  // tot, x, y, z, par, perp, body_x, body_y, body_z
  int dimension = 1;
  std::vector<double> msd, msd_error, msd4, ngp, ngp_error, beta, beta_error;
  Estimate diffusion;  // slope / (2d) over the fit window, jackknife error
};

struct MsdResult {
  std::vector<double> lag;            // mean lag time of each class
  std::vector<double> origins;        // particle-origin pairs per replica per class
  std::vector<MsdComponent> components;
  double fit_t_min = 0, fit_t_max = 0;
  bool fit_window_automatic = true;
  double fit_mean_beta = 0;           // mean β of the total MSD over the fit window
  std::string ngp_constant;           // what the total NGP used
  std::vector<Vec3> directors;        // per replica (director reference)
  std::vector<double> director_order; // per replica
  std::string director_species;       // whose director it is, when not the analysed species' own (spheres)
  std::size_t samples = 0;            // replicas, or blocks for one replica
  std::optional<Estimate> par_over_perp;       // D_par / D_perp, with par and perp components
  std::optional<Estimate> body_par_over_perp;  // D_body_z / mean(D_body_x, D_body_y), with body components
  bool uniform_frames = false;
  const MsdComponent& component(const std::string& name) const;
};

class MsdAnalysis {
 public:
  MsdAnalysis(MsdSettings settings, std::size_t replicas, std::string config_file = "");
  /// Adds one replica (particles of species `species_index`, all if < 0).
  void accumulate(const Trajectory& t, int species_index);
  MsdResult compute() const;
  /// The mean MSD of component `name` (MsdResult::component names) in each error sample (replica,
  /// or block of time origins for one replica) on the lag classes: what the errors and the
  /// jackknife of quantities derived from the MSD (passive microrheology) are made of.
  CurveSamples samples_of(const std::string& name) const;

 private:
  struct Impl;
  MsdSettings s_;
  std::size_t replicas_;
  std::string config_file_;
  LagGrid grid_;
  std::vector<std::string> names_;
  std::vector<int> dims_;
  std::vector<double> lag_sum_;
  std::vector<double> origin_count_;
  CurveSamples samples_;
  std::size_t replicas_seen_ = 0;
  MsdResult meta_;
};

/// Direction of the director of body axis `axis` (−1: the axis with the largest U), from the Q
/// tensor averaged over all frames; `order` receives its U.
Vec3 run_averaged_director(const Trajectory& t, const std::vector<std::size_t>& members, int& axis, double& order);

/// The species whose director is the reference of species `analysed` (spec 50 §1.1): the species
/// itself when it is anisotropic; for spheres (no axes of their own) the anisotropic species of the
/// file — the one named by `director_species` when there are several. A name given for an
/// anisotropic species, an unknown or spherical one, or no anisotropic species → InputError.
int director_species_of(const Trajectory& t, int analysed, const std::string& director_species, const std::string& config_file);

}  // namespace anisodyn::analysis

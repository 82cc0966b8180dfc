#pragma once
// Steady-flow profiles of anisodyn-dpd runs (spec 30 §6, §8) from the per-row profile observables
// the engine's `profiles` key records (profile_z_count, profile_z_vx_sum; profile_r_count,
// profile_r_midplane_count, profile_r_midplane_vx_sum; each a mean over its row's steps):
//
//   slabs along z   density ρ(z) = ⟨n_k⟩ / (A w), velocity v_x(z) = Σ v_x / Σ n over the rows;
//   around a colloid ρ(r) = ⟨n_k⟩ / (4π/3 ((k + 1)³ − k³) w³), and v_x(r) in the mid-plane slab.
//
// Samples are the replicas (or, for a single replica, `blocks` contiguous blocks of its rows). Every
// value comes from the pooled sums of all samples; its standard error is the jackknife over the
// samples (leave one out, replica_statistics.hpp's jackknife_curve), which also serves the ratios
// v = Σv/Σn and b = a/G.
//
// Slip length (spec 30 §6): a least-squares line v_x = G z + a through the slab velocities whose
// centres lie in [fit_from, fit_to]; b = a/G (the distance below z = 0 at which the line reaches
// zero; b > 0 is slip); v_top = Σ v_x / Σ n over the slabs in [top_from, top_to); γ̇ = v_top/height.
// With slabs, v_x_mean = Σ v_x / Σ n over all of them (the mean flow past a fixed colloid, §8).
//
// Periodic Poiseuille flow (no walls; a drive of +f along x on z in [0, h) and −f on [h, 2h), the
// box 2h tall): in steady state η v'' = ∓ρ f in each half, so v_x = ±A u (h − u) + B with u the
// height above the half's bottom and A = ρ f / (2η). A least-squares line of the slab velocities
// against x = ±u (h − u) gives A, and η = ρ f / (2A) with ρ the mean density of all slabs.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "anisodyn/core/statistics.hpp"

namespace anisodyn::analysis {

struct SlipFitSettings {
  double fit_from = 1.5, fit_to = 5.0;  // spec 30 §6
  double top_from = 7.0, top_to = 8.0;
  double height = 8.0;                  // H of γ̇ = v_top/H
};

struct PoiseuilleSettings {
  double force = 0.0;  // f, the drive along x on the lower half of the box (−f on the upper)
};

/// One sample's sums over its rows (each row's per-step means, summed), and the bin geometry.
struct ProfileSums {
  double rows = 0;
  std::vector<double> z_count, z_vx, r_count, r_mid_count, r_mid_vx;
};

struct FlowGeometry {
  double z_bin = 0.0, area = 0.0;  // slabs (0: none)
  double r_bin = 0.0;              // shells (0: none)
};

/// The samples of one run: its rows with `keep(time)` in `blocks` contiguous blocks (1: the run is
/// one sample), and the geometry. InputError naming the file when it has neither kind of profile.
struct RunProfiles {
  FlowGeometry geometry;
  std::vector<ProfileSums> samples;
};
RunProfiles read_profiles(const std::string& path, std::size_t blocks, const std::function<bool(double)>& keep);

struct ValueError {
  double value = 0.0, error = 0.0;
};

struct FlowResult {
  std::vector<double> z, density_z, density_z_se, vx_z, vx_z_se;
  std::vector<double> r, density_r, density_r_se, vx_r, vx_r_se;
  std::optional<ValueError> slip_length, gradient, v_top, shear_rate;
  std::optional<ValueError> v_mean;  // Σ v_x / Σ n over all slabs: the liquid's mean flow velocity
  std::optional<ValueError> poiseuille_amplitude, viscosity;  // A and η of the periodic Poiseuille fit
  std::size_t samples = 0, rows = 0, fit_bins = 0;
};

FlowResult compute_flow(const FlowGeometry& geometry, const std::vector<ProfileSums>& samples, const std::optional<SlipFitSettings>& slip,
                        const std::optional<PoiseuilleSettings>& poiseuille = std::nullopt);

}  // namespace anisodyn::analysis

#pragma once
// Flat walls of a DPD channel (spec 30 §6): planes z = 0 (bottom) and z = H (top), each with the
// colloids' pseudo-hard core and friction shell (interactions/site_liquid.hpp) as for a sphere of
// diameter 0. For a liquid particle at signed distance r from a wall (r = z for the bottom wall,
// H − z for the top one; z unwrapped), with n the wall's normal into the liquid:
//
//   core      U(r) = the shifted Mie(50,49) with Δ = −1: U(0) = ε, cut at r = 0.0204; force −U'(r) n;
//   friction  F^F = −ξ(r) v,  ξ(r) = γ_ls,0 (δ − r)/δ for r < δ (the wall is at rest);
//   noise     F^S = √(2 k_BT ξ(r)/Δt) θ⃗ (vector3d), or θ v̂ (along_v; none if |v| < 1e-12),
//             keyed by (noise step, wall 0 | 1, liquid id) under its own purpose tag.
//
// The walls are fixed: the opposite forces go to them, not to particles, so the liquid's momentum
// changes by what the walls take (last_sums() gives it, per wall). The box must be taller than H by
// at least the DPD cut-off, so that no DPD pair reaches across the periodic boundary in z (the
// engine checks); the loop is serial, in particle order, so its sums have the same bits on any
// number of threads.
#include <array>
#include <cstdint>
#include <span>

#include "anisodyn/core/keyed_random.hpp"
#include "anisodyn/integrate/body_forces.hpp"
#include "anisodyn/interactions/site_liquid.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn {

struct FlatWallParameters {
  double height = 8.0;                         // H: the top wall's plane
  std::array<double, 2> gamma_surface{0, 0};   // γ_ls,0 of the bottom and the top wall
  double shell = 0.5;                          // δ
  double kT = 1.0;
  SiteLiquidParameters::ShellNoise noise = SiteLiquidParameters::ShellNoise::Vector3d;
};

/// The walls' energy with the liquid and the force the liquid exerts on each wall (bottom, top).
struct WallSums {
  double energy = 0.0;
  std::array<Vec3, 2> force_on_wall{Vec3::Zero(), Vec3::Zero()};
};

/// Purpose tag of the walls' shell noise ("WALLNZ").
inline constexpr std::uint64_t kWallNoise = 0x57414c4c4e5aULL;

class FlatWalls {
 public:
  FlatWalls(FlatWallParameters params, double time_step, std::uint64_t seed);

  void set_noise_step(std::uint64_t step) { noise_step_ = step; }
  /// The signed distance of unwrapped height z from wall w (0: bottom, 1: top).
  double distance(int w, double z) const { return w == 0 ? z : p_.height - z; }
  /// ξ(r) of wall w.
  double friction(int w, double r) const;
  /// Adds the walls' forces on the listed liquid particles of s into out (and the energy).
  void add(const State& s, std::span<const std::int32_t> liquid, BodyForces& out);
  const WallSums& last_sums() const { return sums_; }
  const FlatWallParameters& parameters() const { return p_; }
  const ShiftedMieCore& core() const { return core_; }

 private:
  FlatWallParameters p_;
  double time_step_;
  ShiftedMieCore core_;
  KeyedRandom noise_;
  std::uint64_t noise_step_ = 0;
  WallSums sums_;
};

}  // namespace anisodyn

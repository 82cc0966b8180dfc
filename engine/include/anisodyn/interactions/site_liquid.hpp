#pragma once
// Colloid sites and liquid particles (spec 30 §4): the pseudo-hard core and the friction shell with
// its noise, between each site of diameter d (a colloid sphere, or one sphere of a rod) and each
// liquid particle i at r = |r_i − r_s|, r̂ = (r_i − r_s)/r, v_is = v_i − v_s:
//
//   core      U(r) = Mie(50,49) of r − Δ, σ = 1, cut at its minimum and shifted by +ε
//             (Δ = d/2 − 1: U = ε at r = d/2 for every d), force −U'(r) r̂ on i;
//   friction  F^F = −ξ(r) v_is,   ξ(r) = γ_ls,0 (d/2 + δ − r)/δ for r < d/2 + δ
//             (γ_ls,0 at the surface, 0 at the shell's outer edge, growing inside the core);
//   noise     F^S = √(2 k_BT ξ(r)/Δt) θ⃗_is   (vector3d, the default: three unit normals), or
//             F^S = √(2 k_BT ξ(r)/Δt) θ_is v̂_is  (along_v, the printed form; none if |v_is| < 1e-12).
//
// The site receives the opposite of each force (Newton's third law), so the total momentum is
// kept. v_s is the velocity of the site centre (for a rod's site, the rigid-body velocity there):
// the published model. With surface_velocity (spec 30's open point, a variant for study) it is the
// velocity of the surface point nearest the particle, v_s + ω × (d/2) r̂ with ω the body's angular
// velocity, and the site also receives the torque (d/2) r̂ × (−F^F − F^S) about its centre (the
// core is central: no torque).
// The noise is keyed by (noise step, site id, liquid id) under its own purpose tag, independent of
// the DPD pair noise. There are no DPD forces between sites and liquid (spec 30 §3.3).
//
// Every site is checked against every liquid particle: a box holds one colloid (spec 30 §3.3) of
// at most a dozen sites, so this is a few hundred thousand distance tests per step. The liquid
// particles are split into fixed chunks whatever the thread count; each liquid particle adds its
// sites in site order, and each site adds its chunks in chunk order: the same bits on any number
// of threads.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "anisodyn/core/box.hpp"
#include "anisodyn/core/keyed_random.hpp"
#include "anisodyn/core/types.hpp"
#include "anisodyn/interactions/mie_pairs.hpp"

namespace anisodyn {

struct SiteLiquidParameters {
  double shell = 0.5;          // δ, the friction shell's thickness
  double gamma_surface = 0.0;  // γ_ls,0, the friction at the surface
  double kT = 1.0;              // of the noise (0: no noise)
  double epsilon = 1.0;         // the core's ε (spec 30: k_BT = 1)
  enum class ShellNoise { Vector3d, AlongV } noise = ShellNoise::Vector3d;
  bool surface_velocity = false;  // friction on the surface point's velocity (above), not the centre's
};

/// The site–liquid core: MieCore (n = 50, m = 49, ε, σ = 1) of r − Δ, Δ = d/2 − 1.
struct ShiftedMieCore {
  MieCore core;
  double shift(double d) const { return 0.5 * d - 1.0; }
  double cutoff(double d) const { return core.cutoff_ratio() + shift(d); }
  double energy(double r, double d) const { return core.energy(r - shift(d), 1.0); }
  /// −dU/dr (> 0: repulsive).
  double force(double r, double d) const { return core.force(r - shift(d), 1.0); }
};

/// A site as the force loop sees it: centre, velocity of the centre, diameter, noise key, and the
/// body's angular velocity (read only with surface_velocity).
struct SiteView {
  Vec3 position = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();
  double diameter = 1.0;
  std::uint64_t id = 0;
  Vec3 angular_velocity = Vec3::Zero();
};

/// The liquid as the force loop sees it: n particles, structure of arrays.
struct LiquidView {
  const double *x, *y, *z, *vx, *vy, *vz;
  const std::int64_t* id;
  std::size_t n;
};

/// Energy (core) and the virial Σ r_is ⊗ F_is of the core, friction and noise, F on the liquid.
struct SiteLiquidSums {
  double energy = 0.0;
  std::array<Mat3, 3> virial{Mat3::Zero(), Mat3::Zero(), Mat3::Zero()};
};

/// Purpose tag of the shell noise in the keyed generator ("SHELLNZ").
inline constexpr std::uint64_t kShellNoise = 0x5348454c4c4e5aULL;

class SiteLiquidForces {
 public:
  SiteLiquidForces(SiteLiquidParameters params, double time_step, std::uint64_t seed);

  void set_noise_step(std::uint64_t step) { noise_step_ = step; }
  /// ξ(r) for a site of diameter d.
  double friction(double r, double d) const;
  /// Adds the forces on the liquid (3 per particle, x y z), the forces on the sites and the
  /// torques on them about their centres (one each per site; torques only with surface_velocity).
  void add(const Box& box, std::span<const SiteView> sites, const LiquidView& liquid, double* f_liquid, std::span<Vec3> f_sites,
           std::span<Vec3> t_sites);
  const SiteLiquidSums& last_sums() const { return sums_; }
  const SiteLiquidParameters& parameters() const { return p_; }
  const ShiftedMieCore& core() const { return core_; }

 private:
  SiteLiquidParameters p_;
  double time_step_;
  ShiftedMieCore core_;
  KeyedRandom noise_;
  std::uint64_t noise_step_ = 0;
  SiteLiquidSums sums_;
  std::vector<double> partial_;  // per chunk of liquid: the force and torque on each site, then the sums
};

}  // namespace anisodyn

#pragma once
// The colloids of a DPD run and their forces with the liquid (spec 30 §3–§4): which particles are
// colloids and which are liquid, each colloid species' body of sites (dpd/colloid_bodies.hpp), and
// the site–liquid core, friction shell and noise (interactions/site_liquid.hpp) added into the
// run's forces.
//
// Per evaluation: the liquid is gathered into arrays (ascending state index); every colloid's sites
// are placed at r + R(q) d_s and move with the rigid-body velocity V + ω × R(q) d_s, ω the lab-frame
// angular velocity of the body's angular momentum; the site–liquid forces go to the liquid
// particles and, reduced to a force and a torque (system/rigid_sites.hpp), to the colloids; with
// `friction_velocity: "surface"` each site's torque about its centre is added too. A site's
// noise key is (colloid id) · 2⁸ + site index, so that it differs from every other site's.
//
// The checks that make a colloid input bad (InputError with the key that is at fault):
//   - a species that is neither liquid nor colloid, or both; a colloid shape that is not a sphere
//     or spherocylinder;
//   - a colloid whose extent with its interaction reach (length + 2 (d/2 + δ) along its axis) does
//     not fit in the shortest box edge: a liquid particle would then see two images of it;
//   - two colloids whose cores overlap (site distance below the mean of their diameters).
// (The time step's limit from the Mie core is the runner's check: walls have the same core.)
#include <cstdint>
#include <string>
#include <vector>

#include "anisodyn/dpd/colloid_bodies.hpp"
#include "anisodyn/dpd/dpd_protocol.hpp"
#include "anisodyn/integrate/body_forces.hpp"
#include "anisodyn/integrate/rigid_body_nve.hpp"
#include "anisodyn/interactions/site_liquid.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn {

/// Per step: Σ M V² and Σ L·ω over the colloids (twice their kinetic energies).
struct ColloidKinetics {
  double translational = 0.0, rotational = 0.0;
};

class ColloidCoupling {
 public:
  /// Sorts the state's particles into liquid (species with is_liquid set) and colloids (those of
  /// protocol.colloids, which must be set) and checks the input (above). `config_file` names the
  /// file of InputErrors about keys.
  ColloidCoupling(const State& state, const std::vector<char>& is_liquid, const DpdProtocol& protocol, std::uint64_t seed,
                  const std::string& config_file);

  const std::vector<std::int32_t>& liquid() const { return liquid_; }
  const std::vector<std::int32_t>& colloids() const { return colloids_; }
  /// The body of each species (a colloid species' own; empty sites for the liquid's).
  const std::vector<ColloidBody>& bodies() const { return bodies_; }
  /// Mass and principal moments per species, for the integrator.
  std::vector<BodyInertia> inertia(const SpeciesTable& species) const;
  /// Rotational degrees of freedom of all colloids together.
  int rotational_degrees(const State& state) const;

  void set_noise_step(std::uint64_t step) { forces_.set_noise_step(step); }
  /// Adds the site–liquid forces of state s into out (forces, torques, energy, virial).
  void operator()(const State& s, BodyForces& out);
  const SiteLiquidSums& last_sums() const { return forces_.last_sums(); }
  ColloidKinetics kinetics(const State& s) const;

 private:
  Vec3 angular_velocity(const State& s, std::size_t i) const;
  void classify(const State& state, const std::vector<char>& is_liquid, const DpdProtocol& protocol, const std::string& config_file);
  void check_geometry(const State& state, const DpdProtocol& protocol, const std::string& config_file) const;
  void gather_liquid(const Particles& p);
  void place_sites(const State& s);

  std::vector<ColloidBody> bodies_;
  std::vector<std::int32_t> liquid_, colloids_;
  SiteLiquidForces forces_;
  bool fixed_;  // the colloids are held in place
  // Scratch kept between evaluations.
  std::vector<double> lx_, ly_, lz_, lvx_, lvy_, lvz_, f_liquid_;
  std::vector<std::int64_t> lid_;
  std::vector<SiteView> sites_;
  std::vector<Vec3> f_sites_, t_sites_;
};

}  // namespace anisodyn

#pragma once
// Initial configurations for any mixture of species: boxes sized for a packing fraction, aligned
// or random orientations, placement on a lattice or by random non-overlapping insertion, and
// insertion of extra particles (tracers) into an existing configuration.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "anisodyn/core/error.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn {

/// How the particles of one species are oriented.
struct OrientationRule {
  enum class Mode { Aligned, Random } mode = Mode::Aligned;
  int body_axis = 2;                // aligned: this body axis (0 = T, 1 = W, 2 = L) along `director`
  Vec3 director = Vec3::UnitZ();
  bool random_azimuth = false;      // aligned: random rotation about the director (uniaxial start)
};

/// Default alignment axis of spec 10 §3.2: L for prolate boards (W < √(L T)) and spherocylinders,
/// T for oblate boards.
int default_alignment_axis(const Shape& shape);

/// Box edges (proportional to `aspect`) giving packing fraction `eta` for these particles.
Vec3 box_edges_for_packing_fraction(const SpeciesTable& species, const std::vector<std::size_t>& counts,
                                    double eta, const Vec3& aspect);

/// Raised when the particles do not fit (lattice too dense, random insertion stuck).
class PlacementFailure : public RuntimeFailure {
 public:
  using RuntimeFailure::RuntimeFailure;
};

/// Request: `counts[s]` new particles of species s, with orientation rule `rules[s]`.
struct PlacementRequest {
  std::vector<std::size_t> counts;
  std::vector<OrientationRule> rules;
  std::size_t max_attempts_per_particle = 10000;
};

/// Appends the particles on a rectangular lattice filling the box; the lattice spacing along each
/// axis is the largest axis-aligned extent of any particle, so nothing overlaps.
void place_on_lattice(State& state, const PlacementRequest& request, Rng& rng);

/// Appends the particles at independent uniformly random positions without any overlap test: an
/// ideal-gas start for soft particles (a DPD liquid), whose shapes do not exclude each other.
void place_uniformly(State& state, const PlacementRequest& request, Rng& rng);
/// One particle at the centre of the box (a body at infinite dilution, in a pore or between walls:
/// spec 40 §6–7); PlacementFailure for any other count.
void place_at_centre(State& state, const PlacementRequest& request, Rng& rng);

/// Appends the particles one by one at uniformly random positions, rejecting positions that
/// overlap anything already present (largest particles first).
void insert_randomly(State& state, const PlacementRequest& request, Rng& rng);

/// Whether point r lies inside the body of particle i (spheres and spherocylinders; the DPD
/// colloids). InputError for other shapes.
bool inside_body(const State& state, std::size_t i, const Vec3& r);

/// Appends `count` point particles of species `liquid` (a DPD liquid, spec 30 §5) at uniformly
/// random positions outside the bodies of the particles already present: a position inside one is
/// drawn again; z is drawn in [z_min, z_max). PlacementFailure when a particle needs more than
/// max_attempts draws.
void fill_liquid(State& state, int liquid, std::size_t count, Rng& rng, double z_min, double z_max, std::size_t max_attempts = 10000);

}  // namespace anisodyn

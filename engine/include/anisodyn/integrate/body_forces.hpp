#pragma once
// Forces and torques on the bodies of a state, as a force field hands them to an integrator.
#include <cstddef>
#include <functional>
#include <vector>

#include "anisodyn/core/types.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn {

/// Below this many bodies a loop over them runs on one thread: a parallel region costs more than it
/// saves (the integrators' loops and BodyForces::reset).
inline constexpr std::size_t kParallelBodies = 1024;

/// Per body, in particle order: the force and the torque about the body centre, both lab frame;
/// bodies made of sites get them from reduce_site_forces (system/rigid_sites.hpp). The energy is the
/// potential energy of the configuration and the virial W = Σ_{i<j} r_ij ⊗ F_ij (as in
/// interactions/pair_forces.hpp); integrators do not use them, observers may.
struct BodyForces {
  std::vector<Vec3> force, torque;
  double energy = 0;
  Mat3 virial = Mat3::Zero();

  /// n bodies, every force, torque, the energy and the virial zero.
  /// Zeroed by the threads in the integrators' static split of the bodies, so that each thread's
  /// part stays in its own core's cache.
  void reset(std::size_t n) {
    force.resize(n);
    torque.resize(n);
#pragma omp parallel for schedule(static) if (n >= kParallelBodies)
    for (std::size_t i = 0; i < n; ++i) force[i].setZero(), torque[i].setZero();
    energy = 0;
    virial.setZero();
  }
};

/// Computes the forces of a state. The integrator calls it with `out` reset to the state's size,
/// so a field may add its terms into it.
using ForceField = std::function<void(const State&, BodyForces&)>;

}  // namespace anisodyn

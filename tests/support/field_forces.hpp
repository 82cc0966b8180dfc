#pragma once
// What a force field (integrate/body_forces.hpp; e.g. PairForceField) adds for a state, starting from
// zero forces, torques, energy and virial.
#include "anisodyn/integrate/body_forces.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn::testing_support {

template <class Field>
BodyForces forces_of(Field& field, const State& s) {
  BodyForces out;
  out.reset(s.particles.size());
  field(s, out);
  return out;
}

}  // namespace anisodyn::testing_support

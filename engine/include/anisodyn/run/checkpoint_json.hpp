#pragma once
// JSON forms of what engines put in their checkpoints' state: vectors, matrices, and the forces a
// velocity-Verlet integrator carries into its next step (RigidBodyNve::forces; DPD, LB), all with
// their full double precision, so that a restart continues bit for bit.
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/core/types.hpp"
#include "anisodyn/integrate/body_forces.hpp"

namespace anisodyn::run {

nlohmann::json vec3_json(const Vec3& v);
Vec3 vec3_from_json(const nlohmann::json& j);
nlohmann::json mat3_json(const Mat3& m);
Mat3 mat3_from_json(const nlohmann::json& j);
/// x, y, z of each vector in turn.
std::vector<double> flatten(const std::vector<Vec3>& vs);

/// {"force": [...], "torque": [...], "energy", "virial"}.
nlohmann::json body_forces_json(const BodyForces& f);
BodyForces body_forces_from_json(const nlohmann::json& j);

}  // namespace anisodyn::run

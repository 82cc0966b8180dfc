#pragma once
// Rigid bodies made of sites: the overlapping spheres of a DPD rod (spec 30 §3.2), the beads of an
// LB raspberry (spec 40 §4–§5). A body is a particle of the state (centre r, orientation q, body →
// lab); its sites sit at fixed offsets d_s in the body frame, so site s is at r + R(q) d_s.
//
// The reduction of site forces to the body's force and torque lives here and nowhere else. It
// takes the lever arms from the rotated offsets R(q) d_s, never from site positions minus the
// centre: a wrapped site can sit across the periodic boundary from its centre.
#include <cstdint>
#include <span>
#include <vector>

#include "anisodyn/core/types.hpp"

namespace anisodyn {

/// The sites of one species' body. The offsets are from the body centre (about which the body
/// rotates and the torque is taken), in the body frame. Radii and types are optional: empty, or
/// one per site; a type is a role the engine defines (raspberry outer, inner, fill or centre bead).
struct SiteBody {
  std::vector<Vec3> offsets;
  std::vector<double> radii;
  std::vector<std::int32_t> types;

  std::size_t size() const { return offsets.size(); }
};

/// One SiteBody per species index.
using SiteTable = std::vector<SiteBody>;

/// Force and torque on a body, lab frame; the torque is about the body centre.
struct Wrench {
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();
};

/// out[s] = centre + R(q) d_s for every site (out.size() == body.size()). Not wrapped: wrap them
/// with Box::wrap where a cell grid needs it.
void site_positions(const SiteBody& body, const Vec3& centre, const Quat& q, std::span<Vec3> out);

/// F = Σ_s f_s and τ = Σ_s [(R(q) d_s) × f_s + t_s], for the lab-frame forces f_s on the body's
/// sites in site order (site_forces.size() == body.size()) and the torques t_s on the sites about
/// their own centres (site_torques: empty for none, else one per site; DPD's surface friction).
Wrench reduce_site_forces(const SiteBody& body, const Quat& q, std::span<const Vec3> site_forces,
                          std::span<const Vec3> site_torques = {});

/// The lab-frame angular velocity ω = R(q) I⁻¹ R(q)ᵀ L of a body with principal moments I (body
/// axes) and lab-frame angular momentum L; axes of zero moment (a linear rotor's) do not turn.
Vec3 angular_velocity(const Quat& q, const Vec3& angular_momentum, const Vec3& moments);

/// Principal moments of inertia of equal point masses at the offsets, about the body centre and
/// the body axes: the diagonal of Σ_s m (|d_s|² 1 − d_s d_sᵀ). The body axes must be principal
/// axes and the centre the centre of mass (rigid-body integrators assume both): InputError when
/// the centroid or an off-diagonal element is not zero to 1e-10 of the offsets' scale.
Vec3 point_mass_moments(std::span<const Vec3> offsets, double site_mass);

}  // namespace anisodyn

#pragma once
// The analytic checks of study D0 (spec 60 D0; spec 40 §5, §8–9) as measurements: the raspberry
// analysis run on synthetic motion with known answers, and the spheroid geometry against brute
// force. `anisodyn-lb-checks` (suite "analytic") writes them; the unit tests assert on them.
#include <array>
#include <cstdint>
#include <vector>

#include "anisodyn/core/types.hpp"

namespace anisodyn::analysis::checks {

/// A mean over independent samples with its standard error, and the value it should have.
struct Recovered {
  double value = 0.0, error = 0.0, expected = 0.0;
  double pull() const { return (value - expected) / error; }
};

/// Independent rigid bodies diffusing with body-frame D_t,i and D_r,i (body x the symmetry axis),
/// a reference vector at polar angle α from it: the lag curves of analysis/raspberry_diffusion.hpp
/// at one frame interval (τ = 1), each against its expectation (spec 40 §8.2–8.4):
/// lab MSD 2ΣD_t,i; reference-vector angle² 2[D_r,x sin²α + D_r,y(1 + cos²α)] (4D_r for a sphere);
/// three-axis angle² 12 D̄_r; body MSD 2D_t,i and projected angle² 2D_r,i per axis.
struct SyntheticBody {
  Recovered lab_msd, reference_angle, three_axis;
  std::array<Recovered, 3> body_msd, body_angle;
};
SyntheticBody synthetic_body(const Vec3& dt_body, const Vec3& dr_body, double alpha, int bodies, int intervals, std::uint64_t seed);

/// Free Brownian motion (D per axis) started uniformly in a disk of radius `gap` about the pore axis,
/// through the pore-frame analysis of spec 40 §9 at one lag: per β bin the mean square per pore axis,
/// which free motion gives as 2D on every axis (S = 1).
struct PoreFrameFree {
  std::vector<double> beta, count;
  std::array<std::vector<double>, 3> ratio, error;  ///< measured / 2D per pore axis (x radial, y azimuthal, z axial)
  double worst_pull = 0.0;                          ///< the largest |ratio − 1|/SE over bins from β = 0.2 with ≥ 2000 samples
  int bins_checked = 0;
};
PoreFrameFree pore_frame_free_motion(double D, double gap, int runs, int steps, std::uint64_t seed);

/// The distance from r to the ellipsoid of semi-axes s by the bisection of lb/raspberry.hpp, and by
/// a brute-force search over a (θ, φ) grid refined around its best point.
struct NearestPoint {
  double bisection = 0.0, brute_force = 0.0;  ///< the two distances
  double off_surface = 0.0;                   ///< |Σ(p_i/s_i)² − 1| of the bisection's point
  double point_difference = 0.0;              ///< between the two nearest points
};
NearestPoint nearest_point_against_brute_force(const Vec3& semi_axes, const Vec3& r);

}  // namespace anisodyn::analysis::checks

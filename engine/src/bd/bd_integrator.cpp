#include "anisodyn/bd/bd_integrator.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "anisodyn/core/keyed_random.hpp"

namespace anisodyn {

namespace {
/// Particles from which a step is spread over the OpenMP threads.
constexpr std::size_t kParallelFrom = 1024;

/// Purpose tag of the BD noise in KeyedRandom ("BD noise" in ASCII).
constexpr std::uint64_t kBdNoise = 0x4244206e6f697365ULL;

/// q turned by the smallest rotation taking unit vector u to unit vector v: the half-way
/// quaternion (1 + u·v, u × v), normalised. Well conditioned for the small turns of a BD step
/// (u·v ≈ 1); it would fail only for v = −u, which a step cannot reach.
Quat turned(const Quat& q, const Vec3& u, const Vec3& v) {
  const Vec3 w = u.cross(v);
  return (Quat(1.0 + u.dot(v), w.x(), w.y(), w.z()).normalized() * q).normalized();
}

/// Clips v to norm `cap`; returns whether it did.
bool clip(Vec3& v, const std::optional<double>& cap) {
  if (!cap) return false;
  const double n = v.norm();
  if (n <= *cap) return false;
  v *= *cap / n;
  return true;
}
}  // namespace

void perpendicular_basis(const Vec3& u, Vec3& e1, Vec3& e2) {
  // Cross with the lab axis least aligned with u: well conditioned for every u.
  const Vec3 a = std::abs(u.x()) <= std::abs(u.y()) && std::abs(u.x()) <= std::abs(u.z()) ? Vec3::UnitX()
                 : std::abs(u.y()) <= std::abs(u.z())                                       ? Vec3::UnitY()
                                                                                            : Vec3::UnitZ();
  e1 = u.cross(a).normalized();
  e2 = u.cross(e1);
}

BdIntegrator::BdIntegrator(BdSettings settings, ForceField forces) : settings_(std::move(settings)), field_(std::move(forces)) {
  if (!(settings_.time_step > 0.0)) throw std::invalid_argument("the time step must be positive");
  if (!(settings_.kT > 0.0)) throw std::invalid_argument("kT must be positive");
  for (std::size_t s = 0; s < settings_.diffusion.size(); ++s) {
    const BdDiffusion& d = settings_.diffusion[s];
    if (!(d.parallel >= 0.0 && d.perpendicular >= 0.0 && d.rotation >= 0.0))
      throw std::invalid_argument("negative diffusion coefficient for species " + std::to_string(s));
  }
}

void BdIntegrator::restore_counters(std::int64_t capped_forces, std::int64_t capped_torques) {
  capped_forces_ = capped_forces;
  capped_torques_ = capped_torques;
}

double BdIntegrator::step(State& state) {
  Particles& p = state.particles;
  const std::size_t n = p.size();
  forces_.reset(n);
  if (field_) field_(state, forces_);
  const double dt = settings_.time_step, kT = settings_.kT;
  const KeyedRandom noise(settings_.seed, kBdNoise);
  const auto step = static_cast<std::uint64_t>(state.step);
  std::int64_t capped_f = 0, capped_t = 0;
  // About 0.2 µs per particle: below a few thousand particles a parallel region costs more than it
  // saves, and with more threads than free cores its barrier stalls every step.
#pragma omp parallel for schedule(static) reduction(+ : capped_f, capped_t) if (n >= kParallelFrom)
  for (std::size_t i = 0; i < n; ++i) {
    const BdDiffusion& d = settings_.diffusion[static_cast<std::size_t>(p.species[i])];
    Vec3 f = forces_.force[i], t = forces_.torque[i];
    capped_f += clip(f, settings_.force_cap);
    capped_t += clip(t, settings_.torque_cap);
    const Quat q = p.orientation(i);
    const Vec3 u = q * Vec3::UnitZ();
    Vec3 e1, e2;
    perpendicular_basis(u, e1, e2);
    double xi[5];
    noise.normals(step, i, settings_.replica, xi, 5);

    // Translation: mobility (D/kT) split along and across û, noise in the same frame.
    const double f_par = f.dot(u);
    Vec3 r = p.position(i) + (d.parallel / kT) * f_par * dt * u + (d.perpendicular / kT) * dt * (f - f_par * u) +
             std::sqrt(2.0 * d.parallel * dt) * xi[0] * u +
             std::sqrt(2.0 * d.perpendicular * dt) * (xi[1] * e1 + xi[2] * e2);
    Int3 image = p.image(i);
    state.box.wrap(r, image);
    p.set_position(i, r);
    p.set_image(i, image);

    if (d.rotation > 0.0) {
      const double amplitude = std::sqrt(2.0 * d.rotation * dt);
      const Vec3 moved = u + (d.rotation / kT) * dt * t.cross(u) + amplitude * (xi[3] * e1 + xi[4] * e2);
      p.set_orientation(i, turned(q, u, moved.normalized()));
    }
  }
  capped_forces_ += capped_f;
  capped_torques_ += capped_t;
  return dt;
}

}  // namespace anisodyn

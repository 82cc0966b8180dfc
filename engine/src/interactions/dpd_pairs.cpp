#include "anisodyn/interactions/dpd_pairs.hpp"

#include <cmath>

namespace anisodyn {

DpdForceField::DpdForceField(DpdParameters params, double time_step, std::uint64_t seed, int nspecies, double skin)
    : p_(params),
      noise_amplitude_(std::sqrt(2.0 * params.gamma * params.kT / time_step)),
      noise_(seed, kDpdPairNoise),
      list_(std::vector<double>(static_cast<std::size_t>(nspecies * nspecies), params.cutoff), nspecies, skin) {}

void DpdForceField::operator()(const State& s, BodyForces& out) {
  const Particles& p = s.particles;
  const std::size_t n = p.size();
  list_.update(s.box, p);
  slot_force_.resize(3 * list_.pairs());
  partial_.resize(kPerParticle * n);
  const double* x = p.x.data();
  const double* y = p.y.data();
  const double* z = p.z.data();
  const double* vx = p.vx.data();
  const double* vy = p.vy.data();
  const double* vz = p.vz.data();
  const std::int64_t* id = p.id.data();
  const Vec3 L = s.box.edges(), inv = s.box.inverse_edges();
  const double rc = p_.cutoff, rc2 = rc * rc, inv_rc = 1.0 / rc;
  const double a = p_.a, gamma = p_.gamma, sigma = noise_amplitude_, half_energy = 0.5 * a * rc;
  const std::uint64_t step = noise_step_;

  // Pass 1: each pair once, from its lower index; the force on i into the pair's slot.
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    double sum[kPerParticle] = {};
    const double xi = x[i], yi = y[i], zi = z[i], vxi = vx[i], vyi = vy[i], vzi = vz[i];
    const auto idi = static_cast<std::uint64_t>(id[i]);
    std::size_t slot = list_.first_pair_above(i);
    for (const std::int32_t jj : list_.partners_above(i)) {
      const auto j = static_cast<std::size_t>(jj);
      double* f = slot_force_.data() + 3 * slot++;
      // r_ij = r_i − r_j, minimum image
      double dx = xi - x[j], dy = yi - y[j], dz = zi - z[j];
      dx -= L.x() * std::nearbyint(dx * inv.x());
      dy -= L.y() * std::nearbyint(dy * inv.y());
      dz -= L.z() * std::nearbyint(dz * inv.z());
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (r2 >= rc2) {
        f[0] = f[1] = f[2] = 0.0;
        continue;
      }
      const double r = std::sqrt(r2), inv_r = 1.0 / r;
      const double ex = dx * inv_r, ey = dy * inv_r, ez = dz * inv_r;
      const double w = 1.0 - r * inv_rc;
      const double along = ex * (vxi - vx[j]) + ey * (vyi - vy[j]) + ez * (vzi - vz[j]);
      const auto idj = static_cast<std::uint64_t>(id[j]);
      const double theta = noise_.pair_normal(step, idi, idj);
      const double parts[3] = {a * w, -gamma * w * w * along, sigma * w * theta};
      const double total = parts[0] + parts[1] + parts[2];
      f[0] = total * ex;
      f[1] = total * ey;
      f[2] = total * ez;
      sum[0] += half_energy * w * w;
      // r_ij ⊗ F_ij = f_k r (r̂ ⊗ r̂): xx, yy, zz, xy, xz, yz
      const double q[6] = {r * ex * ex, r * ey * ey, r * ez * ez, r * ex * ey, r * ex * ez, r * ey * ez};
      for (int k = 0; k < 3; ++k)
        for (int m = 0; m < 6; ++m) sum[1 + 6 * k + m] += parts[k] * q[m];
    }
    for (int m = 0; m < kPerParticle; ++m) partial_[kPerParticle * i + static_cast<std::size_t>(m)] = sum[m];
  }

  // Pass 2: each particle sums its slots in the order of its full list, with the sign of its side.
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    double fx = 0.0, fy = 0.0, fz = 0.0;
    const auto partners = list_.partners(i);
    const auto slots = list_.pair_slots(i);
    for (std::size_t m = 0; m < partners.size(); ++m) {
      const double* f = slot_force_.data() + 3 * static_cast<std::size_t>(slots[m]);
      if (static_cast<std::size_t>(partners[m]) > i) {
        fx += f[0];
        fy += f[1];
        fz += f[2];
      } else {
        fx -= f[0];
        fy -= f[1];
        fz -= f[2];
      }
    }
    out.force[i] += Vec3(fx, fy, fz);
  }

  sums_ = DpdSums{};
  double total[kPerParticle] = {};
  for (std::size_t i = 0; i < n; ++i)
    for (int m = 0; m < kPerParticle; ++m) total[m] += partial_[kPerParticle * i + static_cast<std::size_t>(m)];
  sums_.energy = total[0];
  for (std::size_t k = 0; k < 3; ++k) {
    const double* v = total + 1 + 6 * k;
    Mat3& w = sums_.virial[k];
    w << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
    out.virial += w;
  }
  out.energy += sums_.energy;
}

}  // namespace anisodyn

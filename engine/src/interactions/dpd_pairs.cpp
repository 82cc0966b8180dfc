#include "anisodyn/interactions/dpd_pairs.hpp"

#include <cmath>

namespace anisodyn {

DpdForceField::DpdForceField(DpdParameters params, double time_step, std::uint64_t seed, double skin)
    : p_(params),
      noise_amplitude_(std::sqrt(2.0 * params.gamma * params.kT / time_step)),
      noise_(seed, kDpdPairNoise),
      list_(params.cutoff, skin) {}

void DpdForceField::gather(const Particles& p) {
  const std::size_t n = p.size();
  x_.resize(n);
  y_.resize(n);
  z_.resize(n);
  vx_.resize(n);
  vy_.resize(n);
  vz_.resize(n);
  id_.resize(n);
  const std::int32_t* order = list_.order().data();
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(order[k]);
    x_[k] = p.x[i];
    y_[k] = p.y[i];
    z_[k] = p.z[i];
    vx_[k] = p.vx[i];
    vy_[k] = p.vy[i];
    vz_[k] = p.vz[i];
    id_[k] = static_cast<std::uint64_t>(p.id[i]);
  }
}

void DpdForceField::operator()(const State& s, BodyForces& out) {
  const Particles& p = s.particles;
  const std::size_t n = p.size();
  list_.update(s.box, p.x.data(), p.y.data(), p.z.data(), n);
  gather(p);
  slot_force_.resize(3 * list_.pairs());
  row_force_.resize(3 * n);
  partial_.resize(kPerParticle * n);
  const Vec3 L = s.box.edges(), inv = s.box.inverse_edges();
  const double rc = p_.cutoff, rc2 = rc * rc, inv_rc = 1.0 / rc;
  const double a = p_.a, gamma = p_.gamma, sigma = noise_amplitude_, half_energy = 0.5 * a * rc;
  const std::uint64_t step = noise_step_;

  // Pass 1: each pair once, from its lower position: the force on that one into its own sum and
  // the pair's slot.
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < n; ++k) {
    double sum[kPerParticle] = {};
    double fk[3] = {0.0, 0.0, 0.0};
    const double xk = x_[k], yk = y_[k], zk = z_[k], vxk = vx_[k], vyk = vy_[k], vzk = vz_[k];
    const std::uint64_t idk = id_[k];
    double* f = slot_force_.data() + 3 * list_.first_pair(k);
    for (const std::int32_t jj : list_.partners_above(k)) {
      const auto j = static_cast<std::size_t>(jj);
      // r_kj = r_k − r_j, minimum image
      double dx = xk - x_[j], dy = yk - y_[j], dz = zk - z_[j];
      dx -= L.x() * std::nearbyint(dx * inv.x());
      dy -= L.y() * std::nearbyint(dy * inv.y());
      dz -= L.z() * std::nearbyint(dz * inv.z());
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (r2 >= rc2) {
        f[0] = f[1] = f[2] = 0.0;
        f += 3;
        continue;
      }
      const double r = std::sqrt(r2), inv_r = 1.0 / r;
      const double ex = dx * inv_r, ey = dy * inv_r, ez = dz * inv_r;
      const double w = 1.0 - r * inv_rc;
      const double along = ex * (vxk - vx_[j]) + ey * (vyk - vy_[j]) + ez * (vzk - vz_[j]);
      const double theta = noise_.pair_normal(step, idk, id_[j]);
      const double parts[3] = {a * w, -gamma * w * w * along, sigma * w * theta};
      const double total = parts[0] + parts[1] + parts[2];
      f[0] = total * ex;
      f[1] = total * ey;
      f[2] = total * ez;
      fk[0] += f[0];
      fk[1] += f[1];
      fk[2] += f[2];
      f += 3;
      sum[0] += half_energy * w * w;
      // r_kj ⊗ F_kj = f_m r (r̂ ⊗ r̂): xx, yy, zz, xy, xz, yz
      const double q[6] = {r * ex * ex, r * ey * ey, r * ez * ez, r * ex * ey, r * ex * ez, r * ey * ez};
      for (int m = 0; m < 3; ++m)
        for (int e = 0; e < 6; ++e) sum[1 + 6 * m + e] += parts[m] * q[e];
    }
    for (int m = 0; m < 3; ++m) row_force_[3 * k + static_cast<std::size_t>(m)] = fk[m];
    for (int m = 0; m < kPerParticle; ++m) partial_[kPerParticle * k + static_cast<std::size_t>(m)] = sum[m];
  }

  // Pass 2: each position takes the opposite of its pairs from below, in ascending order.
  const std::int32_t* order = list_.order().data();
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < n; ++k) {
    double fx = row_force_[3 * k], fy = row_force_[3 * k + 1], fz = row_force_[3 * k + 2];
    for (const std::int32_t slot : list_.lower_pairs(k)) {
      const double* f = slot_force_.data() + 3 * static_cast<std::size_t>(slot);
      fx -= f[0];
      fy -= f[1];
      fz -= f[2];
    }
    out.force[static_cast<std::size_t>(order[k])] += Vec3(fx, fy, fz);
  }

  sums_ = DpdSums{};
  double total[kPerParticle] = {};
  for (std::size_t k = 0; k < n; ++k)
    for (int m = 0; m < kPerParticle; ++m) total[m] += partial_[kPerParticle * k + static_cast<std::size_t>(m)];
  sums_.energy = total[0];
  for (std::size_t m = 0; m < 3; ++m) {
    const double* v = total + 1 + 6 * m;
    Mat3& w = sums_.virial[m];
    w << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
    out.virial += w;
  }
  out.energy += sums_.energy;
}

}  // namespace anisodyn

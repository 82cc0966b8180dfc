#include "anisodyn/interactions/dpd_pairs.hpp"

#include <algorithm>
#include <cmath>

#ifdef _OPENMP
#include <omp.h>
#endif

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

namespace {

/// One pair's force on its lower position and, for the sums, its parts and geometry.
struct PairTerms {
  double f[3];
  double parts[3];  // conservative, dissipative, random, along r̂
  double r, e[3], w;
};

}  // namespace

// Not inlined: the pairs across blocks are evaluated twice, once into their slot and once for
// their row, and both must give the same bits; one compiled body guarantees it (inlined into the
// two versions of the loop, the compiler could contract the arithmetic differently, and did).
/// d: r_k − r_j before the minimum image; false when the pair is beyond the cut-off.
[[gnu::noinline]] static bool pair_terms(double* d, const Vec3& L, const Vec3& inv, double rc2, PairTerms& t) {
  for (int e = 0; e < 3; ++e) d[e] -= L[e] * std::nearbyint(d[e] * inv[e]);
  const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  if (r2 >= rc2) return false;
  t.r = std::sqrt(r2);
  const double inv_r = 1.0 / t.r;
  for (int m = 0; m < 3; ++m) t.e[m] = d[m] * inv_r;
  return true;
}

/// The force of a pair within the cut-off (pair_terms filled r and e): dv = v_k − v_j.
[[gnu::noinline]] static void pair_force(const double* dv, double theta, const DpdParameters& p, double sigma, PairTerms& t) {
  t.w = 1.0 - t.r / p.cutoff;
  const double along = t.e[0] * dv[0] + t.e[1] * dv[1] + t.e[2] * dv[2];
  t.parts[0] = p.a * t.w;
  t.parts[1] = -p.gamma * t.w * t.w * along;
  t.parts[2] = sigma * t.w * theta;
  const double total = t.parts[0] + t.parts[1] + t.parts[2];
  for (int m = 0; m < 3; ++m) t.f[m] = total * t.e[m];
}

void DpdForceField::rows(std::size_t begin, std::size_t end, std::size_t block_end, bool cross_only, const Box& box) {
  const Vec3 L = box.edges(), inv = box.inverse_edges();
  const double rc2 = p_.cutoff * p_.cutoff, sigma = noise_amplitude_, half_energy = 0.5 * p_.a * p_.cutoff;
  const std::uint64_t step = noise_step_;
  double* force = force_.data();
  for (std::size_t k = begin; k < end; ++k) {
    const auto row = list_.partners_above(k);
    // Cross pairs (partner beyond the block) are the row's tail: partners ascend.
    const std::size_t cross = static_cast<std::size_t>(std::lower_bound(row.begin(), row.end(), static_cast<std::int32_t>(block_end)) - row.begin());
    if (cross_only && cross == row.size()) continue;
    double sum[kPerParticle] = {};
    const double xk = x_[k], yk = y_[k], zk = z_[k], vxk = vx_[k], vyk = vy_[k], vzk = vz_[k];
    const std::uint64_t idk = id_[k];
    for (std::size_t m = cross_only ? cross : 0; m < row.size(); ++m) {
      const auto j = static_cast<std::size_t>(row[m]);
      double d[3] = {xk - x_[j], yk - y_[j], zk - z_[j]};  // r_kj = r_k − r_j
      PairTerms t;
      if (!pair_terms(d, L, inv, rc2, t)) {
        if (cross_only) std::fill_n(slot_force_.data() + 3 * (list_.first_pair(k) + m), 3, 0.0);  // the owner of j reads it
        continue;
      }
      const double dv[3] = {vxk - vx_[j], vyk - vy_[j], vzk - vz_[j]};
      pair_force(dv, noise_.pair_normal(step, idk, id_[j]), p_, sigma, t);
      const double* f = t.f;
      if (cross_only) {
        double* slot = slot_force_.data() + 3 * (list_.first_pair(k) + m);
        slot[0] = f[0], slot[1] = f[1], slot[2] = f[2];
        continue;
      }
      force[3 * k] += f[0];
      force[3 * k + 1] += f[1];
      force[3 * k + 2] += f[2];
      if (j < block_end) {
        force[3 * j] -= f[0];
        force[3 * j + 1] -= f[1];
        force[3 * j + 2] -= f[2];
      }
      sum[0] += half_energy * t.w * t.w;
      // r_kj ⊗ F_kj = f_m r (r̂ ⊗ r̂): xx, yy, zz, xy, xz, yz
      const double q[6] = {t.r * t.e[0] * t.e[0], t.r * t.e[1] * t.e[1], t.r * t.e[2] * t.e[2],
                           t.r * t.e[0] * t.e[1], t.r * t.e[0] * t.e[2], t.r * t.e[1] * t.e[2]};
      for (int n = 0; n < 3; ++n)
        for (int e = 0; e < 6; ++e) sum[1 + 6 * n + e] += t.parts[n] * q[e];
    }
    if (!cross_only)
      for (int n = 0; n < kPerParticle; ++n) partial_[kPerParticle * k + static_cast<std::size_t>(n)] = sum[n];
  }
}

void DpdForceField::operator()(const State& s, BodyForces& out) {
  const Particles& p = s.particles;
  const std::size_t n = p.size();
  list_.update(s.box, p.x.data(), p.y.data(), p.z.data(), n);
  gather(p);
  if (slot_force_.size() < 3 * list_.pairs()) slot_force_.resize(3 * list_.pairs());
  force_.assign(3 * n, 0.0);
  partial_.resize(kPerParticle * n);

  // Each thread owns a block of positions. Every position's force is the sum, in this order, of
  // the opposites of its pairs from below (ascending) and then its pairs above (ascending), for any
  // number of blocks: first the pairs that reach into a later block leave their force in their
  // slot; then each block takes the slots that reach into it, all from lower positions than its
  // own, and walks its rows, adding each pair to both positions when both are its own.
#pragma omp parallel
  {
    int blocks = 1, b = 0;  // the threads the region got
#ifdef _OPENMP
    blocks = omp_get_num_threads();
    b = omp_get_thread_num();
#endif
    const auto block_begin = [&](int k) { return n * static_cast<std::size_t>(k) / static_cast<std::size_t>(blocks); };
    const std::size_t begin = block_begin(b), end = block_begin(b + 1);
    if (blocks > 1) rows(begin, end, end, true, s.box);
#pragma omp barrier
    const std::size_t own_slots = list_.first_pair(begin);
    for (std::size_t k = begin; k < end; ++k)
      for (const std::int32_t slot : list_.lower_pairs(k)) {
        if (static_cast<std::size_t>(slot) >= own_slots) break;
        const double* f = slot_force_.data() + 3 * static_cast<std::size_t>(slot);
        force_[3 * k] -= f[0];
        force_[3 * k + 1] -= f[1];
        force_[3 * k + 2] -= f[2];
      }
    rows(begin, end, end, false, s.box);
    const std::int32_t* order = list_.order().data();
    for (std::size_t k = begin; k < end; ++k)
      out.force[static_cast<std::size_t>(order[k])] += Vec3(force_[3 * k], force_[3 * k + 1], force_[3 * k + 2]);
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

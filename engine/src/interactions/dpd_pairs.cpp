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

void DpdForceField::set_liquid(std::vector<std::int32_t> indices) {
  liquid_ = std::move(indices);
  subset_ = true;
  list_.invalidate();
}

void DpdForceField::gather(const Particles& p, std::size_t n) {
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
    const std::size_t i = particle(static_cast<std::size_t>(order[k]));
    x_[k] = p.x[i];
    y_[k] = p.y[i];
    z_[k] = p.z[i];
    vx_[k] = p.vx[i];
    vy_[k] = p.vy[i];
    vz_[k] = p.vz[i];
    id_[k] = static_cast<std::uint32_t>(p.id[i]);  // below 2³² (checked by the engine)
  }
}

void DpdForceField::update_list(const State& s, std::size_t n) {
  const Particles& p = s.particles;
  if (!subset_) {
    list_.update(s.box, p.x.data(), p.y.data(), p.z.data(), n);
    return;
  }
  lx_.resize(n);
  ly_.resize(n);
  lz_.resize(n);
#pragma omp parallel for schedule(static)
  for (std::size_t u = 0; u < n; ++u) {
    const std::size_t i = particle(u);
    lx_[u] = p.x[i];
    ly_[u] = p.y[i];
    lz_[u] = p.z[i];
  }
  list_.update(s.box, lx_.data(), ly_.data(), lz_.data(), n);
}

namespace {

/// Σ_q term(q) with eight partial sums combined in a fixed order: the association is the
/// source's, so the sum has the same bits on any thread, and the loop vectorises
/// (inlined into row_forces by force: left to itself, the compiler once called it per sum, 22% of a step).
template <class Term>
[[gnu::always_inline]] inline double fixed_sum(std::size_t n, Term term) {
  double acc[8] = {};
  std::size_t q = 0;
  for (; q + 8 <= n; q += 8)
    for (std::size_t l = 0; l < 8; ++l) acc[l] += term(q + l);
  for (std::size_t l = 0; q + l < n; ++l) acc[l] += term(q + l);
  return ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]));
}

}  // namespace

void DpdForceField::row_forces(const RowTask* tasks, std::size_t count, std::size_t block_end, bool cross_only, const Box& box) {
  const Vec3 L = box.edges(), inv = box.inverse_edges();
  const double rc = p_.cutoff, rc2 = rc * rc, inv_rc = 1.0 / rc;
  const double a = p_.a, gamma = p_.gamma, sigma = noise_amplitude_, half_energy = 0.5 * a * rc;
  // Scratch of this thread, grown as needed: the candidates of all the rows, then those within the
  // cut-off, gathered without a branch (half of the candidates are, at random), then their forces
  // in a loop the compiler vectorises, then the sums.
  thread_local std::vector<double> dx, dy, dz, r2, theta, e0, e1, e2, rr, pc, pd, pr, en, q0, q1, q2, q3, q4, q5;
  thread_local std::vector<std::uint32_t> task_of, within, id_a, id_b, kk, jj;
  std::size_t candidates = 0;
  for (std::size_t t = 0; t < count; ++t) candidates += tasks[t].m_end - tasks[t].m_begin;
  if (dx.size() < candidates) {
    for (auto* v : {&dx, &dy, &dz, &r2, &theta, &e0, &e1, &e2, &rr, &pc, &pd, &pr, &en, &q0, &q1, &q2, &q3, &q4, &q5}) v->resize(2 * candidates);
    for (auto* v : {&task_of, &within, &id_a, &id_b, &kk, &jj}) v->resize(2 * candidates);
  }
  // The candidates within the cut-off, in candidate order, written at the next free place without a
  // branch (the place advances only for those inside; about half are, at random). Their task and
  // candidate number only where pairs go to slots (cross_only): the fewer stores, the faster.
  std::size_t inside = 0;
  const auto keep_within = [&]<bool kSlots>() {
    double *__restrict sx = dx.data(), *__restrict sy = dy.data(), *__restrict sz = dz.data(), *__restrict s2 = r2.data();
    std::uint32_t *__restrict pk = kk.data(), *__restrict pj = jj.data(), *__restrict pt = task_of.data(), *__restrict pw = within.data();
    const double *__restrict px = x_.data(), *__restrict py = y_.data(), *__restrict pz = z_.data();
    std::size_t c = 0;
    for (std::size_t t = 0; t < count; ++t) {
      const RowTask& task = tasks[t];
      const double xk = px[task.k], yk = py[task.k], zk = pz[task.k];
      const auto k = static_cast<std::uint32_t>(task.k);
      const std::int32_t* row = list_.partners_above(task.k).data();
      for (std::size_t m = task.m_begin; m < task.m_end; ++m, ++c) {
        const auto j = static_cast<std::uint32_t>(row[m]);
        // r_kj = r_k − r_j, minimum image
        double ddx = xk - px[j], ddy = yk - py[j], ddz = zk - pz[j];
        ddx -= L.x() * std::nearbyint(ddx * inv.x());
        ddy -= L.y() * std::nearbyint(ddy * inv.y());
        ddz -= L.z() * std::nearbyint(ddz * inv.z());
        const double d2 = ddx * ddx + ddy * ddy + ddz * ddz;
        sx[inside] = ddx, sy[inside] = ddy, sz[inside] = ddz, s2[inside] = d2;
        pk[inside] = k, pj[inside] = j;
        if constexpr (kSlots) pt[inside] = static_cast<std::uint32_t>(t), pw[inside] = static_cast<std::uint32_t>(c);
        inside += d2 < rc2 ? 1 : 0;
      }
    }
  };
  if (cross_only) keep_within.template operator()<true>();
  else keep_within.template operator()<false>();
  {
    const std::uint32_t *__restrict ids = id_.data(), *__restrict pk = kk.data(), *__restrict pj = jj.data();
    std::uint32_t *__restrict ia = id_a.data(), *__restrict ib = id_b.data();
#pragma omp simd
    for (std::size_t q = 0; q < inside; ++q) ia[q] = ids[pk[q]], ib[q] = ids[pj[q]];
  }
  // The noise of all pairs within the cut-off in one batch (vectorised: core/pair_noise.hpp).
  noise_.normals(noise_step_, id_a.data(), id_b.data(), inside, theta.data());
  {
    // Plain pointers that cannot alias, so that the compiler vectorises the loop (gathers of the
    // velocities); the arithmetic is the same, lane by lane.
    const double* __restrict vx = vx_.data();
    const double* __restrict vy = vy_.data();
    const double* __restrict vz = vz_.data();
    const std::uint32_t* __restrict pk = kk.data();
    const std::uint32_t* __restrict pj = jj.data();
    const double *__restrict sx = dx.data(), *__restrict sy = dy.data(), *__restrict sz = dz.data(), *__restrict s2 = r2.data();
    const double* __restrict th = theta.data();
    double *__restrict out_r = rr.data(), *__restrict out_x = e0.data(), *__restrict out_y = e1.data(), *__restrict out_z = e2.data();
    double *__restrict out_c = pc.data(), *__restrict out_d = pd.data(), *__restrict out_n = pr.data();
    // For the sums: the pair energy and r r̂ ⊗ r̂ (xx, yy, zz, xy, xz, yz), which times each part's
    // magnitude is that part's r_kj ⊗ F_kj.
    double *__restrict out_e = en.data(), *__restrict o0 = q0.data(), *__restrict o1 = q1.data(), *__restrict o2 = q2.data();
    double *__restrict o3 = q3.data(), *__restrict o4 = q4.data(), *__restrict o5 = q5.data();
#pragma omp simd
    for (std::size_t q = 0; q < inside; ++q) {
      const std::uint32_t k = pk[q], j = pj[q];
      const double r = std::sqrt(s2[q]), inv_r = 1.0 / r;
      const double ex = sx[q] * inv_r, ey = sy[q] * inv_r, ez = sz[q] * inv_r;
      const double w = 1.0 - r * inv_rc;
      const double along = ex * (vx[k] - vx[j]) + ey * (vy[k] - vy[j]) + ez * (vz[k] - vz[j]);
      out_r[q] = r, out_x[q] = ex, out_y[q] = ey, out_z[q] = ez;
      out_c[q] = a * w;
      out_d[q] = -gamma * w * w * along;
      out_n[q] = sigma * w * th[q];
      out_e[q] = half_energy * w * w;
      o0[q] = r * ex * ex, o1[q] = r * ey * ey, o2[q] = r * ez * ez;
      o3[q] = r * ex * ey, o4[q] = r * ex * ez, o5[q] = r * ey * ez;
    }
  }
  if (!cross_only && inside > 0) {
    // The group's sums (one call holds the rows of one group), each a fixed-order sum over its pairs.
    double* sum = partial_.data() + kSums * (tasks[0].k / kRowsPerGroup);
    const double* pair_energy = en.data();
    sum[0] += fixed_sum(inside, [&](std::size_t q) { return pair_energy[q]; });
    const double* parts[3] = {pc.data(), pd.data(), pr.data()};
    const double* geometry[6] = {q0.data(), q1.data(), q2.data(), q3.data(), q4.data(), q5.data()};
    for (int n = 0; n < 3; ++n)
      for (int e = 0; e < 6; ++e) {
        const double *x = parts[n], *y = geometry[e];
        sum[1 + 6 * n + e] += fixed_sum(inside, [&](std::size_t q) { return x[q] * y[q]; });
      }
  }
  double* force = force_.data();
  for (std::size_t q = 0; q < inside; ++q) {
    const std::size_t k = kk[q], j = jj[q];
    const double total = pc[q] + pd[q] + pr[q];
    const double f[3] = {total * e0[q], total * e1[q], total * e2[q]};
    if (cross_only) {
      // Into the pair's slot, for the owner of j.
      const RowTask& task = tasks[task_of[q]];
      double* slot = slot_force_.get() + 3 * (list_.first_pair(k) + task.m_begin + (within[q] - task.first_candidate));
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
  }
}

void DpdForceField::rows(std::size_t begin, std::size_t end, const Box& box) {
  // Rows go to row_forces in groups (aligned to multiples of kRowsPerGroup: blocks start at such
  // multiples), so that the noise of a group is drawn in one batch.
  thread_local std::vector<RowTask> tasks;  // this thread's, kept between calls
  for (std::size_t group = begin; group < end; group += kRowsPerGroup) {
    const std::size_t group_end = std::min(end, group + kRowsPerGroup);
    tasks.clear();
    std::fill_n(partial_.data() + kSums * (group / kRowsPerGroup), kSums, 0.0);
    std::size_t candidates = 0;
    for (std::size_t k = group; k < group_end; ++k) {
      const std::size_t size = list_.partners_above(k).size();
      tasks.push_back({k, 0, size, candidates});
      candidates += size;
    }
    row_forces(tasks.data(), tasks.size(), end, false, box);
  }
}

void DpdForceField::find_cross_tasks(std::size_t begin, std::size_t end, std::vector<RowTask>& cross) const {
  cross.clear();
  std::size_t candidates = 0;
  for (std::size_t k = begin; k < end; ++k) {
    // Pairs across the block (partner at or beyond end) are the row's tail: partners ascend.
    const auto row = list_.partners_above(k);
    const auto m_begin = static_cast<std::size_t>(std::lower_bound(row.begin(), row.end(), static_cast<std::int32_t>(end)) - row.begin());
    if (m_begin == row.size()) continue;
    cross.push_back({k, m_begin, row.size(), candidates});
    candidates += row.size() - m_begin;
  }
}

namespace {

/// The candidates of a block's cross tasks (numbered in order from 0).
template <class Task>
std::size_t candidates_of(const std::vector<Task>& tasks) {
  return tasks.empty() ? 0 : tasks.back().first_candidate + (tasks.back().m_end - tasks.back().m_begin);
}

}  // namespace

void DpdForceField::cross_share(int share, int shares, const Box& box) {
  // The pairs across blocks of all blocks, in block order, as one sequence of candidates: this
  // thread takes the tasks that start in its equal part of it. (Each block's own tasks would load
  // the first block with the pairs across the periodic boundary as well as those across its end,
  // and leave the last with none.) A pair's slot is the same whoever evaluates it.
  std::size_t total = 0;
  for (const auto& tasks : cross_tasks_) total += candidates_of(tasks);
  const std::size_t lo = total * static_cast<std::size_t>(share) / static_cast<std::size_t>(shares);
  const std::size_t hi = total * static_cast<std::size_t>(share + 1) / static_cast<std::size_t>(shares);
  thread_local std::vector<RowTask> batch;
  std::size_t offset = 0;  // the block's first candidate in the sequence
  for (const auto& tasks : cross_tasks_) {
    const auto starts_before = [&](const RowTask& t, std::size_t c) { return offset + t.first_candidate < c; };
    auto t = std::lower_bound(tasks.begin(), tasks.end(), lo, starts_before);
    const auto t_end = std::lower_bound(t, tasks.end(), hi, starts_before);
    while (t != t_end) {
      batch.clear();
      std::size_t candidates = 0;
      for (; t != t_end && batch.size() < kRowsPerGroup; ++t) {
        batch.push_back({t->k, t->m_begin, t->m_end, candidates});
        candidates += t->m_end - t->m_begin;
        // Pairs beyond the cut-off are not written: their slots hold 0.
        std::fill_n(slot_force_.get() + 3 * (list_.first_pair(t->k) + t->m_begin), 3 * (t->m_end - t->m_begin), 0.0);
      }
      row_forces(batch.data(), batch.size(), 0, true, box);
    }
    offset += candidates_of(tasks);
  }
}

void DpdForceField::operator()(const State& s, BodyForces& out) {
  const Particles& p = s.particles;
  const std::size_t n = subset_ ? liquid_.size() : p.size();  // liquid particles
  if (n == 0) {  // colloids alone (a free body in vacuum)
    sums_ = DpdSums{};
    return;
  }
  update_list(s, n);
  gather(p, n);
  // Uninitialised: only the slots of pairs across blocks are ever written, near the blocks' ends,
  // so the rest of the array never becomes resident memory.
  if (slot_capacity_ < 3 * list_.pairs()) {
    slot_capacity_ = 3 * list_.pairs() + 3 * list_.pairs() / 8;
    slot_force_ = std::make_unique_for_overwrite<double[]>(slot_capacity_);
  }
  force_.resize(3 * n);  // zeroed by the block's thread: only it writes there
  const std::size_t groups = (n + kRowsPerGroup - 1) / kRowsPerGroup;
  partial_.resize(kSums * groups);

  // Each thread owns a block of positions. Every position's force is the sum, in this order, of
  // the opposites of its pairs from below (ascending) and then its pairs above (ascending), for any
  // number of blocks: first the pairs that reach into a later block leave their force in their
  // slot (shared out evenly between the threads); then each block takes the slots that reach into
  // it, all from lower positions than its own, and walks its rows, adding each pair to both
  // positions when both are its own. Which pairs cross depends on the list and the blocks only:
  // found once per list build.
  const std::int64_t cross_builds = cross_builds_;
  const int cross_blocks = cross_blocks_;
#pragma omp parallel
  {
    int blocks = 1, b = 0;  // the threads the region got
#ifdef _OPENMP
    blocks = omp_get_num_threads();
    b = omp_get_thread_num();
#endif
    // Blocks of whole groups of rows, so that a group's sums are one thread's, added in row order;
    // about the same number of pairs in each (the first rows have more pairs above them than the
    // last: their neighbour cells across the periodic boundary are numbered above them).
    const auto block_begin = [&](int k) {
      const std::size_t target = list_.pairs() * static_cast<std::size_t>(k) / static_cast<std::size_t>(blocks);
      std::size_t lo = 0, hi = groups;  // the first group whose first row starts at or after target
      while (lo < hi) {
        const std::size_t mid = (lo + hi) / 2;
        if (list_.first_pair(mid * kRowsPerGroup) < target) lo = mid + 1;
        else hi = mid;
      }
      return k == blocks ? n : std::min(n, lo * kRowsPerGroup);
    };
    const std::size_t begin = block_begin(b), end = block_begin(b + 1);
    std::fill(force_.begin() + static_cast<std::ptrdiff_t>(3 * begin), force_.begin() + static_cast<std::ptrdiff_t>(3 * end), 0.0);
    if (blocks > 1) {
      if (cross_builds != list_.builds() || cross_blocks != blocks) {
#pragma omp single
        cross_tasks_.resize(static_cast<std::size_t>(blocks));
        find_cross_tasks(begin, end, cross_tasks_[static_cast<std::size_t>(b)]);
#pragma omp barrier
      }
      cross_share(b, blocks, s.box);
#pragma omp single nowait
      cross_builds_ = list_.builds(), cross_blocks_ = blocks;
    }
#pragma omp barrier
    const std::size_t own_slots = list_.first_pair(begin);
    for (std::size_t k = begin; k < end; ++k)
      for (const std::int32_t slot : list_.lower_pairs(k)) {
        if (static_cast<std::size_t>(slot) >= own_slots) break;
        const double* f = slot_force_.get() + 3 * static_cast<std::size_t>(slot);
        force_[3 * k] -= f[0];
        force_[3 * k + 1] -= f[1];
        force_[3 * k + 2] -= f[2];
      }
    rows(begin, end, s.box);
    // Each thread writes the forces of the particles it will kick (the integrator's static split of
    // the particle indices), not those of its positions, which are all over the arrays: written by
    // one core and read by the other, each cache line would cross between them.
#pragma omp barrier
    const std::int32_t* position = list_.position_of().data();
#pragma omp for schedule(static)
    for (std::size_t u = 0; u < n; ++u) {
      const auto k = static_cast<std::size_t>(position[u]);
      out.force[particle(u)] += Vec3(force_[3 * k], force_[3 * k + 1], force_[3 * k + 2]);
    }
  }

  sums_ = DpdSums{};
  double total[kSums] = {};
  for (std::size_t g = 0; g < groups; ++g)
    for (int m = 0; m < kSums; ++m) total[m] += partial_[kSums * g + static_cast<std::size_t>(m)];
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

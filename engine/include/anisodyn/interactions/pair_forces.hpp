#pragma once
// Pair forces, written once for every pair interaction: the physics is a small evaluator struct,
// this loop does the neighbours, the energy, the virial and the bookkeeping.
//
// An evaluator provides
//   static constexpr int kParts;   // how many parts its force is split into (DPD: conservative,
//                                  // dissipative, random; most interactions: 1)
//   PairTerm<kParts> operator()(std::size_t i, std::size_t j, const Vec3& d, double r2) const;
// with d = r_j − r_i (minimum image) and r2 = |d|²; it returns the force on i (by part), the torque
// on i and the pair energy. Torques are returned rather than derived from forces because some are
// not lever arms (the BD overlap-volume torque, spec 20 §4.3).
//
// Owner computes: particle i sums the terms of its own partners, in the order of its Verlet list,
// and writes only its own force and torque; each pair is evaluated once from each side. With an
// evaluator that is odd under exchanging i and j (keyed pair noise makes DPD so), both sides get
// exactly opposite forces, so Newton's third law holds pair by pair, and the results are the same
// for any thread count. Energy and virial are halved per side and summed over particles in index
// order, so they are thread-count independent too.
#include <array>
#include <vector>

#include "anisodyn/core/box.hpp"
#include "anisodyn/core/types.hpp"
#include "anisodyn/neighbors/verlet_list.hpp"
#include "anisodyn/system/particles.hpp"

namespace anisodyn {

template <int Parts>
struct PairTerm {
  bool interacts = false;
  std::array<Vec3, Parts> force{};  // on i, by part; the force is their sum
  Vec3 torque = Vec3::Zero();       // on i
  double energy = 0.0;              // of the pair (the loop counts half from each side)
};

template <int Parts>
struct PairSums {
  double energy = 0.0;
  /// W = Σ_{i<j} r_ij ⊗ F_ij per part, r_ij = r_i − r_j and F_ij the force on i from j; the
  /// configurational pressure tensor is W / V.
  std::array<Mat3, Parts> virial;
  PairSums() { virial.fill(Mat3::Zero()); }
};

/// The per-particle energy and virial halves that the sums are reduced from, in index order. A
/// time-stepping engine keeps one between steps so that the loop does not allocate every step.
template <int Parts>
struct PairScratch {
  std::vector<double> energy;
  std::vector<std::array<Mat3, Parts>> virial;
};

/// Sets force[i] (and torque[i], if torque is given) to the sum of the pair terms of particle i
/// over its partners in `list`, which must be up to date; returns energy and virial. `scratch`
/// (optional) is reused storage for the per-particle partial sums.
template <class Eval>
PairSums<Eval::kParts> accumulate_pair_forces(const Box& box, const Particles& p, const VerletList& list, const Eval& eval,
                                              std::vector<Vec3>& force, std::vector<Vec3>* torque = nullptr,
                                              PairScratch<Eval::kParts>* scratch = nullptr) {
  constexpr int kParts = Eval::kParts;
  const std::size_t n = p.size();
  force.resize(n);
  if (torque) torque->resize(n);
  PairScratch<kParts> local;
  PairScratch<kParts>& partial = scratch ? *scratch : local;
  partial.energy.resize(n);  // every entry is overwritten below
  partial.virial.resize(n);
  std::vector<double>& energy = partial.energy;
  std::vector<std::array<Mat3, kParts>>& virial = partial.virial;
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 ri = p.position(i);
    Vec3 f = Vec3::Zero(), t = Vec3::Zero();
    double e = 0.0;
    std::array<Mat3, kParts> w;
    w.fill(Mat3::Zero());
    for (const std::int32_t j : list.partners(i)) {
      const Vec3 d = box.min_image(p.position(static_cast<std::size_t>(j)) - ri);
      const PairTerm<kParts> term = eval(i, static_cast<std::size_t>(j), d, d.squaredNorm());
      if (!term.interacts) continue;
      for (int k = 0; k < kParts; ++k) {
        f += term.force[static_cast<std::size_t>(k)];
        w[static_cast<std::size_t>(k)] -= 0.5 * d * term.force[static_cast<std::size_t>(k)].transpose();  // r_ij = −d
      }
      t += term.torque;
      e += 0.5 * term.energy;
    }
    force[i] = f;
    if (torque) (*torque)[i] = t;
    energy[i] = e;
    virial[i] = w;
  }
  PairSums<kParts> sums;
  for (std::size_t i = 0; i < n; ++i) {
    sums.energy += energy[i];
    for (int k = 0; k < kParts; ++k) sums.virial[static_cast<std::size_t>(k)] += virial[i][static_cast<std::size_t>(k)];
  }
  return sums;
}

}  // namespace anisodyn

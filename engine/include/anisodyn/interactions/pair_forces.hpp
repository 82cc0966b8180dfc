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
//
// Once per pair: an evaluator that declares `static constexpr bool kOncePerPair = true` promises
// that its term for (i, j) also gives the one for (j, i): exactly −force (every part), the same
// energy, and the torque on j in `torque_j`, as the call for (j, i) would return them. Its pairs are
// then evaluated once each (partners above i), the interacting ones recorded by pair number, and
// each particle sums the records of its partners in the order of its full list, with the signs of
// its side: the same terms in the same order as owner computes, at half the evaluations, still
// thread-count independent (both passes write only their own records and particles).
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
  Vec3 torque_j = Vec3::Zero();     // on j: only from evaluators evaluated once per pair
  double energy = 0.0;              // of the pair (the loop counts half from each side)
};

/// A pair's term with its separation d = r_j − r_i (evaluators evaluated once per pair).
template <int Parts>
struct PairRecord {
  PairTerm<Parts> term;
  Vec3 d = Vec3::Zero();
};

template <class Eval>
constexpr bool evaluated_once_per_pair() {
  if constexpr (requires { Eval::kOncePerPair; }) return Eval::kOncePerPair;
  else return false;
}

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
  std::vector<PairRecord<Parts>> pairs;  // once per pair only: the records of interacting pairs,
  std::vector<char> interacts;           // and which pairs interact (most listed pairs do not)
};

namespace detail {
/// One particle's sums over its pairs.
template <int Parts>
struct ParticleSums {
  Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
  double energy = 0.0;
  std::array<Mat3, Parts> virial;
  ParticleSums() { virial.fill(Mat3::Zero()); }
  /// Adds the term of the pair (i, j) seen from i; d = r_j − r_i.
  void add(const PairTerm<Parts>& term, const Vec3& d) {
    for (std::size_t k = 0; k < static_cast<std::size_t>(Parts); ++k) {
      force += term.force[k];
      virial[k] -= 0.5 * d * term.force[k].transpose();  // r_ij = −d
    }
    torque += term.torque;
    energy += 0.5 * term.energy;
  }
};
}  // namespace detail

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
  auto store = [&](std::size_t i, const detail::ParticleSums<kParts>& sum) {
    force[i] = sum.force;
    if (torque) (*torque)[i] = sum.torque;
    energy[i] = sum.energy;
    virial[i] = sum.virial;
  };
  if constexpr (evaluated_once_per_pair<Eval>()) {
    // Records are written for interacting pairs only: writing every listed pair's record made the
    // loop wait on memory.
    std::vector<PairRecord<kParts>>& records = partial.pairs;
    std::vector<char>& interacts = partial.interacts;
    records.resize(list.pairs());
    interacts.resize(list.pairs());
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 ri = p.position(i);
      std::size_t slot = list.first_pair_above(i);
      for (const std::int32_t j : list.partners_above(i)) {
        const Vec3 d = box.min_image(p.position(static_cast<std::size_t>(j)) - ri);
        const PairTerm<kParts> term = eval(i, static_cast<std::size_t>(j), d, d.squaredNorm());
        interacts[slot] = term.interacts;
        if (term.interacts) records[slot] = {term, d};
        ++slot;
      }
    }
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      detail::ParticleSums<kParts> sum;
      const auto partners = list.partners(i);
      const auto slots = list.pair_slots(i);
      for (std::size_t m = 0; m < partners.size(); ++m) {
        const auto slot = static_cast<std::size_t>(slots[m]);
        if (!interacts[slot]) continue;
        const PairRecord<kParts>& r = records[slot];
        if (static_cast<std::size_t>(partners[m]) > i) {
          sum.add(r.term, r.d);
        } else {  // the term of (i, j) from the pair's record (j, i)
          PairTerm<kParts> mine = r.term;
          for (Vec3& part : mine.force) part = -part;
          mine.torque = r.term.torque_j;
          sum.add(mine, Vec3(-r.d));
        }
      }
      store(i, sum);
    }
  } else {
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 ri = p.position(i);
      detail::ParticleSums<kParts> sum;
      for (const std::int32_t j : list.partners(i)) {
        const Vec3 d = box.min_image(p.position(static_cast<std::size_t>(j)) - ri);
        const PairTerm<kParts> term = eval(i, static_cast<std::size_t>(j), d, d.squaredNorm());
        if (term.interacts) sum.add(term, d);
      }
      store(i, sum);
    }
  }
  PairSums<kParts> sums;
  for (std::size_t i = 0; i < n; ++i) {
    sums.energy += energy[i];
    for (int k = 0; k < kParts; ++k) sums.virial[static_cast<std::size_t>(k)] += virial[i][static_cast<std::size_t>(k)];
  }
  return sums;
}

}  // namespace anisodyn

#include "anisodyn/hydro/rigid_body_resistance.hpp"

#include <map>

#include "anisodyn/core/error.hpp"
#include "anisodyn/hydro/mirror_symmetry.hpp"
#include "anisodyn/hydro/rpy.hpp"

namespace anisodyn::hydro {

namespace {

Mat3 cross_matrix(const Vec3& r) {
  Mat3 m;
  m << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return m;
}

/// Velocity of a bead at r under rigid mode e (0..2: translation along x, y, z; 3..5: rotation
/// about x, y, z): u = U + ω × r.
Vec3 rigid_mode_velocity(int e, const Vec3& r) {
  if (e < 3) return Vec3::Unit(e);
  return Vec3::Unit(e - 3).cross(r);
}

/// Character of rigid mode e under the reflection diag(s): a translation is a polar vector
/// (component a picks up s_a), a rotation an axial vector (s_b s_c for the other two axes).
int mode_character(int e, const Vec3& s) {
  if (e < 3) return static_cast<int>(s[e]);
  const int a = e - 3;
  return static_cast<int>(s[(a + 1) % 3] * s[(a + 2) % 3]);
}

/// Rigid modes grouped by their characters over the group: each group is one independent block.
std::vector<std::vector<int>> symmetry_classes(const MirrorSymmetry& sym) {
  std::map<std::vector<int>, std::vector<int>> classes;
  for (int e = 0; e < 6; ++e) {
    std::vector<int> chi;
    for (const auto& op : sym.operations) chi.push_back(mode_character(e, op.sign));
    classes[chi].push_back(e);
  }
  std::vector<std::vector<int>> out;
  for (auto& [chi, modes] : classes) out.push_back(modes);
  return out;
}

struct Unknown {
  std::size_t orbit;
  int component;
};

/// Solves one symmetry block for its modes and adds their resistance entries to K.
///
/// Forces of class χ obey f_{g·j} = χ(g) G_g f_j, so only orbit representatives carry unknowns, and
/// a component that a stabilising reflection would flip against χ must vanish. The reduced matrix
///   Ã[(i,c),(j,d)] = 1/(|H_i||H_j|) Σ_g χ(g) M(r_i, G_g r_j)_{cd} s_g[d]
/// is the mobility restricted to the χ-symmetric subspace, so it is symmetric positive definite.
void solve_block(const BeadModel& model, const MirrorSymmetry& sym, const std::vector<int>& modes,
                 const ResistanceOptions& opt, ResistanceResult& result) {
  const int e0 = modes.front();
  std::vector<int> chi;
  for (const auto& op : sym.operations) chi.push_back(mode_character(e0, op.sign));

  std::vector<Unknown> unknowns;
  for (std::size_t o = 0; o < sym.orbits.size(); ++o)
    for (int c = 0; c < 3; ++c) {
      bool allowed = true;
      for (int h : sym.orbits[o].stabilizer)
        allowed = allowed && chi[static_cast<std::size_t>(h)] * sym.operations[static_cast<std::size_t>(h)].sign[c] > 0;
      if (allowed) unknowns.push_back({o, c});
    }
  const auto n = static_cast<Eigen::Index>(unknowns.size());
  if (n == 0) return;
  result.largest_block = std::max(result.largest_block, unknowns.size());

  const auto& beads = model.centres;
  auto weight = [&](std::size_t o) { return 1.0 / static_cast<double>(sym.orbits[o].stabilizer.size()); };

  // Lower triangle only: the Cholesky factorisation reads nothing else.
  Eigen::MatrixXd A(n, n);
  const auto n_orbits = static_cast<std::ptrdiff_t>(sym.orbits.size());
  std::vector<Eigen::Index> first_unknown(sym.orbits.size() + 1, 0);
  for (const auto& u : unknowns) first_unknown[u.orbit + 1]++;
  for (std::size_t o = 0; o < sym.orbits.size(); ++o) first_unknown[o + 1] += first_unknown[o];
#pragma omp parallel for schedule(dynamic, 16)
  for (std::ptrdiff_t oi = 0; oi < n_orbits; ++oi) {
    const Vec3& ri = beads[sym.orbits[static_cast<std::size_t>(oi)].representative];
    for (std::ptrdiff_t oj = 0; oj <= oi; ++oj) {
      const std::size_t rj = sym.orbits[static_cast<std::size_t>(oj)].representative;
      Mat3 block = Mat3::Zero();
      for (std::size_t g = 0; g < sym.operations.size(); ++g) {
        const Vec3& s = sym.operations[g].sign;
        const Mat3 m = rpy_mobility(ri - beads[sym.operations[g].image[rj]], model.radius, opt.eta);
        block += static_cast<double>(chi[g]) * m * s.asDiagonal();
      }
      block *= weight(static_cast<std::size_t>(oi)) * weight(static_cast<std::size_t>(oj));
      for (Eigen::Index a = first_unknown[static_cast<std::size_t>(oi)]; a < first_unknown[static_cast<std::size_t>(oi) + 1]; ++a)
        for (Eigen::Index b = first_unknown[static_cast<std::size_t>(oj)]; b < first_unknown[static_cast<std::size_t>(oj) + 1]; ++b)
          if (b <= a) A(a, b) = block(unknowns[static_cast<std::size_t>(a)].component, unknowns[static_cast<std::size_t>(b)].component);
    }
  }

  Eigen::MatrixXd rhs(n, static_cast<Eigen::Index>(modes.size()));
  for (Eigen::Index a = 0; a < n; ++a) {
    const auto& u = unknowns[static_cast<std::size_t>(a)];
    const Vec3& r = beads[sym.orbits[u.orbit].representative];
    for (std::size_t k = 0; k < modes.size(); ++k)
      rhs(a, static_cast<Eigen::Index>(k)) = weight(u.orbit) * rigid_mode_velocity(modes[k], r)[u.component];
  }

  Eigen::LLT<Eigen::MatrixXd, Eigen::Lower> llt(A);
  if (llt.info() != Eigen::Success)
    throw RuntimeFailure("bead-model mobility matrix is not positive definite (coincident beads?)");
  const Eigen::MatrixXd forces = llt.solve(rhs);

  // K_{e'e} = Σ over all beads u^{e'}·f^e = Σ over representatives (|G|/|H_i|) u^{e'}_i·f^e_i.
  const double group_order = static_cast<double>(sym.operations.size());
  for (std::size_t k = 0; k < modes.size(); ++k)
    for (std::size_t l = 0; l < modes.size(); ++l) {
      double sum = 0.0;
      for (Eigen::Index a = 0; a < n; ++a) {
        const auto& u = unknowns[static_cast<std::size_t>(a)];
        const Vec3& r = beads[sym.orbits[u.orbit].representative];
        sum += group_order * weight(u.orbit) * rigid_mode_velocity(modes[l], r)[u.component] *
               forces(a, static_cast<Eigen::Index>(k));
      }
      result.resistance(modes[l], modes[k]) = sum;
    }
}

}  // namespace

ResistanceResult rigid_body_resistance(const BeadModel& model, const ResistanceOptions& options) {
  if (model.centres.empty() || !(model.radius > 0.0)) throw InputError("a bead model needs beads of positive radius");
  const MirrorSymmetry sym = find_mirror_symmetry(model.centres, 1e-9 * (1.0 + model.radius), options.use_symmetry);
  ResistanceResult result;
  result.symmetry_order = static_cast<int>(sym.operations.size());
  for (const auto& modes : symmetry_classes(sym)) solve_block(model, sym, modes, options, result);
  // Symmetrise away round-off: K is symmetric exactly.
  result.resistance = 0.5 * (result.resistance + result.resistance.transpose()).eval();
  return result;
}

Mat6 move_reference_point(const Mat6& D, const Vec3& p) {
  const Mat3 P = cross_matrix(p);
  const Mat3 Dtt = D.topLeftCorner<3, 3>(), Dtr = D.topRightCorner<3, 3>(), Drt = D.bottomLeftCorner<3, 3>(),
             Drr = D.bottomRightCorner<3, 3>();
  Mat6 out;
  out.topLeftCorner<3, 3>() = Dtt + Dtr * P - P * Drt - P * Drr * P;
  out.topRightCorner<3, 3>() = Dtr - P * Drr;
  out.bottomLeftCorner<3, 3>() = (Dtr - P * Drr).transpose();
  out.bottomRightCorner<3, 3>() = Drr;
  return out;
}

Vec3 centre_of_diffusion(const Mat6& D) {
  // Antisymmetric part of a 3×3 matrix as a vector; linear in p, so the condition
  // asym(D_tr − [p]× D_rr) = 0 is the 3×3 system L p = asym(D_tr) with columns L e_k = asym([e_k]× D_rr).
  auto asym = [](const Mat3& m) { return Vec3(m(2, 1) - m(1, 2), m(0, 2) - m(2, 0), m(1, 0) - m(0, 1)); };
  const Mat3 Drr = D.bottomRightCorner<3, 3>();
  Mat3 L;
  for (int k = 0; k < 3; ++k) L.col(k) = asym(cross_matrix(Vec3::Unit(k)) * Drr);
  return L.fullPivLu().solve(asym(D.topRightCorner<3, 3>()));
}

double relative_coupling(const Mat6& D) {
  double worst = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      worst = std::max(worst, std::abs(D(i, 3 + j)) / std::sqrt(D(i, i) * D(3 + j, 3 + j)));
  return worst;
}

}  // namespace anisodyn::hydro

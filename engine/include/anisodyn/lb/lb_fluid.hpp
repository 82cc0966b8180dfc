#pragma once
// The fluctuating D3Q19 lattice-Boltzmann fluid of spec 40 §2 (Dünweg, Schiller and Ladd, PRE 76,
// 036704, 2007), in lattice units (a = Δt_LB = 1):
// - collision in mode space (lb/d3q19.hpp): shear modes relaxed with γ_s = (6ν − 1)/(6ν + 1),
//   the bulk mode with γ_b, the ghosts with γ_g; every non-conserved mode k gets the noise
//   φ_k r_k, φ_k = √(μ ρ b_k (1 − γ_k²)), μ = k_BT/c_s², r_k from core/node_noise.hpp keyed by
//   (seed, step, node, k), so a run has the same bits on any number of threads;
// - forcing in mode space (Guo's form): j* = j + f, the stress modes gain (1 + γ_k)/2 times the
//   projection of u f + f u, and the fluid velocity is u = (j + f/2)/ρ everywhere (also in the
//   equilibrium stress);
// - streaming fused with the collision (each row of nodes is collided and pushed to its
//   neighbours in one pass), periodic in all three directions;
// - halfway bounce-back at solid nodes, with the moving-wall term −2 w_i ρ_0 (c_i·u_w)/c_s² for a
//   solid node given a velocity (§2.4).
//
// Populations are stored structure-of-arrays, one array per velocity (population i of node n at
// [i · stride + n], the stride a little over the node count), nodes x-fastest:
// n = x + n_x (y + n_y z); node centres are at (x + ½, y + ½, z + ½).
#include <array>
#include <cstddef>
#include <cstdint>
#include <new>
#include <utility>
#include <vector>

#include "anisodyn/core/node_noise.hpp"
#include "anisodyn/core/types.hpp"
#include "anisodyn/lb/d3q19.hpp"

namespace anisodyn::lb {

/// Storage on whole cache lines, so that a row of populations can be written as whole lines.
template <class T>
struct CacheLineAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlignment{64};
  CacheLineAllocator() = default;
  template <class U>
  CacheLineAllocator(const CacheLineAllocator<U>&) {}
  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlignment)); }
  void deallocate(T* p, std::size_t) { ::operator delete(p, kAlignment); }
  template <class U>
  bool operator==(const CacheLineAllocator<U>&) const {
    return true;
  }
};

/// The fluid's parameters, in lattice units.
struct LbParameters {
  double density = 1.0;           ///< ρ_0: the initial density, and the moving walls' reference
  double viscosity = 1.0 / 6.0;   ///< ν > 0 (τ = 3ν + ½ > ½)
  double bulk_relaxation = 0.0;   ///< γ_b in (−1, 1]; 0: relaxed fully each step (spec 40 §2.3)
  double ghost_relaxation = 0.0;  ///< γ_g in (−1, 1]
  double kT = 0.0;                ///< k_BT; 0: the deterministic fluid
  std::uint64_t seed = 0;

  double shear_relaxation() const { return (6.0 * viscosity - 1.0) / (6.0 * viscosity + 1.0); }
};

class LbFluid {
 public:
  /// A periodic box of dims nodes, every node fluid at rest at the density ρ_0. Throws InputError
  /// for a box of no nodes or more than 2³² − 1, ν ≤ 0, a relaxation outside (−1, 1], k_BT < 0.
  LbFluid(const std::array<int, 3>& dims, const LbParameters& params);

  const std::array<int, 3>& dims() const { return dims_; }
  std::size_t nodes() const { return nodes_; }
  std::size_t node(int x, int y, int z) const {
    return static_cast<std::size_t>(x) + static_cast<std::size_t>(dims_[0]) * (static_cast<std::size_t>(y) + static_cast<std::size_t>(dims_[1]) * static_cast<std::size_t>(z));
  }
  const LbParameters& parameters() const { return params_; }
  std::uint64_t steps() const { return steps_; }

  /// The equilibrium populations of density ρ and velocity u at a node (u as the fluid velocity
  /// (j + f/2)/ρ with no force pending: j = ρ u).
  void set_equilibrium(std::size_t node, double rho, const Vec3& u);

  /// Makes a node solid (no fluid; bounce-back on every link into it), moving with wall_velocity.
  void set_solid(std::size_t node, const Vec3& wall_velocity = Vec3::Zero());
  bool solid(std::size_t node) const { return solid_[node] != 0; }

  /// Adds a force density to the node for the next step only (cleared by step()).
  void add_force(std::size_t node, const Vec3& f);
  /// A force density on every fluid node at every step (a pressure gradient, say).
  void set_body_force(const Vec3& g) { body_force_ = g; }

  /// One LB step: collide every fluid node with the forces of this step, stream, bounce back.
  void step();

  /// Population i of a node (after streaming, before the next collision).
  double population(int i, std::size_t node) const { return f_[static_cast<std::size_t>(i) * stride_ + node]; }
  std::array<double, kQ> modes(std::size_t node) const;
  double density(std::size_t node) const;
  /// j = Σ_i c_i n_i, without the half force.
  Vec3 momentum_density(std::size_t node) const;
  /// The fluid velocity u = (j + f/2)/ρ with the force density pending for the next step, or
  /// j/ρ alone (with_half_force false); a solid node's is its wall velocity (a bead near a wall
  /// interpolates towards it, and the impulse it gives a solid node goes into the wall).
  Vec3 velocity(std::size_t node, bool with_half_force = true) const;
  /// Σ ρ u² over the fluid nodes (u as velocity(): with the half force) and their number: the
  /// fluid's temperature in one pass.
  std::pair<double, std::size_t> kinetic_sum() const;
  /// Σ of the force densities pending for the next step (add_force), over every node.
  Vec3 pending_force_total() const;
  /// Σ ρ and Σ j over the fluid nodes.
  double total_mass() const;
  Vec3 total_momentum() const;

  /// The whole state for a checkpoint: the populations (population i of node n at
  /// [i · nodes + n]), and the step (the noise's counter).
  std::vector<double> populations() const;
  void restore(const std::vector<double>& populations, std::uint64_t steps);
  /// Whether rows are written past the caches (by default where n_x is a multiple of 8 and the
  /// lattice's two copies exceed 32 MB). The bits are the same either way; tests compare the two.
  void use_streaming_stores(bool on);
  bool streaming_stores() const { return streaming_stores_; }

  /// The force densities added for the next step (add_force), x of every node, then y, then z;
  /// with the populations, what a checkpoint between two LB steps needs.
  std::vector<double> pending_forces() const;
  void restore_pending_forces(const std::vector<double>& forces);

 private:
  struct BoundaryLink {
    std::size_t fluid, solid;  ///< the fluid node, its solid neighbour along c_i
    int i;                     ///< the velocity from the fluid node into the solid
    double wall_term;          ///< 2 w_i ρ_0 (c_i·u_w)/c_s²
  };

  Vec3 force_at(std::size_t node) const;
  /// ρ and j of a node (modes 0–3 alone: what velocities and totals need).
  std::array<double, 4> conserved_modes(std::size_t node) const;
  void build_links();
  template <bool Thermal, bool BulkRelaxes, bool GhostsRelax>
  void collide_row(std::size_t row, double* out, double* noise, std::size_t stride) const;
  using RowCollision = void (LbFluid::*)(std::size_t, double*, double*, std::size_t) const;
  /// The collision compiled for this fluid's noise and relaxations.
  RowCollision row_collision() const;
  void stream_row(std::size_t row, double* out, std::size_t stride);
  /// The force densities of a row's nodes, used by its collision, back to zero.
  void clear_row_forces(std::size_t row);
  /// Where population i of a row's nodes goes (their x shifted by c_ix), and fetching those lines
  /// for writing while the row before is collided.
  double* destination(int i, std::size_t row);
  void prefetch_destinations(std::size_t row);

  std::array<int, 3> dims_;
  std::size_t nodes_;
  std::size_t stride_ = 0;  ///< from one population's array to the next
  LbParameters params_;
  double gamma_[kQ];  ///< the relaxation of each mode (1 for the conserved ones)
  double phi_[kQ];    ///< √(μ b_k (1 − γ_k²)): the noise amplitude over √ρ
  NodeNoise noise_;
  std::vector<double, CacheLineAllocator<double>> f_, next_;  ///< populations now, and the next step's
  /// Rows are written with non-temporal stores (whole cache lines, no read for ownership): for a
  /// lattice larger than the caches, where the next step reads them from memory anyway.
  bool streaming_stores_ = false;
  std::vector<double> fx_, fy_, fz_;
  bool forces_pending_ = false;
  Vec3 body_force_ = Vec3::Zero();
  std::vector<unsigned char> solid_;
  std::vector<Vec3> wall_velocity_;  ///< per node (zero for fluid nodes)
  std::vector<BoundaryLink> links_;
  bool links_stale_ = false;
  std::uint64_t steps_ = 0;
};

}  // namespace anisodyn::lb

#include "anisodyn/lb/lb_fluid.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>

#include "anisodyn/core/error.hpp"

#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace anisodyn::lb {

namespace {

inline constexpr std::uint64_t kLbFluidNoise = 0x4C42464C554944ULL;  // "LBFLUID"
constexpr int kNoisyModes = kQ - kFirstStressMode;                     // 15: modes 4–18
/// Below this many nodes a step runs on one thread: the parallel region costs more than it saves,
/// and far more when other processes share the cores (a test suite run two at a time).
constexpr std::size_t kParallelNodes = 4096;

// The transforms between populations and modes use the opposite pairs (i, i + 1), i odd: each
// mode is even or odd under c → −c, so an even mode needs only the pair sums n_i + n_{i+1}, an odd
// one only the differences, and back from the modes a pair is (E + O, E − O) with E the even
// modes' part and O the odd modes'. That halves the arithmetic; within each sum only the non-zero
// e_ki are added (a −0.0 for a zero term adds nothing, and the compiler drops it).
constexpr int kPairs = (kQ - 1) / 2;

constexpr bool odd_mode(int k) {
  for (int p = 0; p < kPairs; ++p)
    if (kE[k][2 * p + 2] != -kE[k][2 * p + 1]) return false;
  return kE[k][0] == 0;
}
constexpr bool even_mode(int k) {
  for (int p = 0; p < kPairs; ++p)
    if (kE[k][2 * p + 2] != kE[k][2 * p + 1]) return false;
  return true;
}
constexpr bool every_mode_has_a_parity() {
  for (int k = 0; k < kQ; ++k)
    if (odd_mode(k) == even_mode(k)) return false;
  return true;
}
static_assert(every_mode_has_a_parity());

/// −0.0: the identity of addition, which the compiler drops from a sum (a +0.0 it must keep, as
/// −0.0 + 0.0 = +0.0).
template <class T>
[[gnu::always_inline]] inline T negative_zero() {
  return -T{};
}

/// e · x, or −0.0 for e = 0.
template <int E, class T>
[[gnu::always_inline]] inline T times(const T& x) {
  if constexpr (E == 0) return negative_zero<T>();
  else if constexpr (E == 1) return x;
  else if constexpr (E == -1) return -x;
  else return static_cast<double>(E) * x;
}

/// Sets of modes as bit masks: which ones a collision computes from the populations, and which
/// ones are non-zero after it. A mode relaxed fully (γ = 0, spec 40's default for bulk and ghosts)
/// is not needed before the collision, and a ghost without noise is zero after it: skipping them
/// takes about half the arithmetic out of the deterministic step.
using ModeSet = std::uint32_t;
constexpr ModeSet modes_below(int k) { return (ModeSet{1} << k) - 1; }
constexpr ModeSet kAllModes = modes_below(kQ);
constexpr ModeSet kConservedModes = modes_below(kFirstStressMode);
constexpr ModeSet kBulkMode = ModeSet{1} << kFirstStressMode;
constexpr ModeSet kShearModes = modes_below(kFirstGhostMode) & ~modes_below(kFirstShearMode);
constexpr ModeSet kGhostModes = kAllModes & ~modes_below(kFirstGhostMode);
constexpr bool in(ModeSet set, int k) { return (set >> k) & 1U; }

/// 1/b_k, exact at compile time (the collision divides by b_k after relaxing).
constexpr std::array<double, kQ> inverse_norms() {
  std::array<double, kQ> inv{};
  for (int k = 0; k < kQ; ++k) inv[k] = 1.0 / kB[k];
  return inv;
}
constexpr std::array<double, kQ> kInvB = inverse_norms();

/// m_K from the rest population and the pair sums (even K) or differences (odd K).
template <int K, class T, int... P>
[[gnu::always_inline]] inline T mode_of(const T& rest, const T* sum, const T* diff, std::integer_sequence<int, P...>) {
  if constexpr (odd_mode(K)) return (negative_zero<T>() + ... + times<kE[K][2 * P + 1]>(diff[P]));
  else return (times<kE[K][0]>(rest) + ... + times<kE[K][2 * P + 1]>(sum[P]));
}

/// The modes in Wanted (the others left as they are).
template <ModeSet Wanted, class T, int... K>
[[gnu::always_inline]] inline void modes_of(const T* n, T* m, std::integer_sequence<int, K...>) {
  T sum[kPairs], diff[kPairs];
  for (int p = 0; p < kPairs; ++p) sum[p] = n[2 * p + 1] + n[2 * p + 2], diff[p] = n[2 * p + 1] - n[2 * p + 2];
  (..., [&] {
    if constexpr (in(Wanted, K)) m[K] = mode_of<K>(n[0], sum, diff, std::make_integer_sequence<int, kPairs>{});
  }());
}

/// Σ_k e_kI s_k over the even (Odd = false) or the odd modes k of Live.
template <ModeSet Live, int I, bool Odd, class T, int... K>
[[gnu::always_inline]] inline T part_of(const T* s, std::integer_sequence<int, K...>) {
  return (negative_zero<T>() + ... + times<in(Live, K) && odd_mode(K) == Odd ? kE[K][I] : 0>(s[K]));
}

/// n_i = w_i Σ_k e_ki s_k over the modes of Live (the others are zero), with s_k = m_k / b_k.
template <ModeSet Live, class T, int... P>
[[gnu::always_inline]] inline void populations_of(const T* s, T* n, std::integer_sequence<int, P...>) {
  constexpr auto modes = std::make_integer_sequence<int, kQ>{};
  n[0] = kW[0] * part_of<Live, 0, false>(s, modes);
  (..., [&] {
    const T even = part_of<Live, 2 * P + 1, false>(s, modes), odd = part_of<Live, 2 * P + 1, true>(s, modes);
    n[2 * P + 1] = kW[2 * P + 1] * (even + odd);
    n[2 * P + 2] = kW[2 * P + 2] * (even - odd);
  }());
}

/// Eight nodes side by side (GCC's vector extension: one AVX-512 register, or two or four
/// narrower ones where the CPU has no AVX-512). The collision works on them, so that it is
/// vectorised whatever the compiler makes of a loop.
using Lanes = double __attribute__((vector_size(64)));
constexpr int kLanes = 8;
/// Two lattice copies up to this size are left to the caches (the last-level cache of the
/// machines measured; the step's own row buffers are small beside it).
constexpr std::size_t kCachedLatticeBytes = std::size_t{32} << 20;
/// How far ahead the read streams are fetched, in nodes (32 to 256 measured alike on 64³).
constexpr std::size_t kPrefetchAhead = 64;

[[gnu::always_inline]] inline Lanes load(const double* p) {
  Lanes v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
[[gnu::always_inline]] inline void store(double* p, const Lanes& v) { std::memcpy(p, &v, sizeof v); }
[[gnu::always_inline]] inline Lanes splat(double a) { return Lanes{} + a; }

/// A whole aligned cache line stored past the caches (no read for ownership).
[[gnu::always_inline]] inline void store_streaming(double* p, const Lanes& v) {
#if defined(__AVX512F__)
  _mm512_stream_pd(p, reinterpret_cast<__m512d>(v));
#elif defined(__AVX__)
  _mm256_stream_pd(p, _mm256_set_pd(v[3], v[2], v[1], v[0]));
  _mm256_stream_pd(p + 4, _mm256_set_pd(v[7], v[6], v[5], v[4]));
#else
  store(p, v);
#endif
}
inline void fence_streaming_stores() {
#if defined(__AVX__)
  _mm_sfence();
#endif
}

std::size_t wrap(long i, int n) { return static_cast<std::size_t>((i % n + n) % n); }

void check_relaxation(double gamma, const char* name) {
  if (!(gamma > -1.0 && gamma <= 1.0))
    throw InputError(std::string("LbFluid: the ") + name + " relaxation must lie in (-1, 1], got " + std::to_string(gamma));
}

}  // namespace

LbFluid::LbFluid(const std::array<int, 3>& dims, const LbParameters& params)
    : dims_(dims), nodes_(0), params_(params), noise_(params.seed, kLbFluidNoise) {
  for (int d = 0; d < 3; ++d)
    if (dims[d] < 1) throw InputError("LbFluid: the lattice needs at least one node along each axis");
  nodes_ = static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1]) * static_cast<std::size_t>(dims[2]);
  if (nodes_ >= (std::size_t{1} << 32)) throw InputError("LbFluid: at most 2^32 - 1 nodes (the noise is keyed by a 32-bit node number)");
  if (!(params.viscosity > 0.0) || !std::isfinite(params.viscosity))
    throw InputError("LbFluid: the kinematic viscosity must be positive (tau = 3 nu + 1/2 > 1/2), got " + std::to_string(params.viscosity));
  if (!(params.density > 0.0) || !std::isfinite(params.density)) throw InputError("LbFluid: the density must be positive");
  if (!(params.kT >= 0.0) || !std::isfinite(params.kT)) throw InputError("LbFluid: k_BT must be zero or positive");
  check_relaxation(params.bulk_relaxation, "bulk");
  check_relaxation(params.ghost_relaxation, "ghost");
  const double mu = params.kT / kCs2;
  for (int k = 0; k < kQ; ++k) {
    gamma_[k] = k < kFirstStressMode ? 1.0 : k == kFirstStressMode ? params.bulk_relaxation : k < kFirstGhostMode ? params.shear_relaxation() : params.ghost_relaxation;
    phi_[k] = k < kFirstStressMode ? 0.0 : std::sqrt(mu * kB[k] * (1.0 - gamma_[k] * gamma_[k]));
  }
  // Each population's array starts three cache lines further into a 4 kB page than the last: at a
  // power-of-two stride (64³ nodes: 2 MB) the nineteen streams of a row map to the same cache sets
  // (measured: 18.4 against 23.6 MLUPS on 64³, docs/performance.md).
  stride_ = (nodes_ + kLanes - 1) / kLanes * kLanes + 3 * kLanes;
  // Past the caches only when the two copies of the lattice do not fit in them anyway: measured
  // 1.9× faster at 48³ and 64³ (34 and 80 MB), 10% slower at 24³ and 32³ (docs/performance.md).
  // Rows start on a cache line only when n_x is a whole number of vectors.
  streaming_stores_ = dims[0] % kLanes == 0 && 2 * kQ * sizeof(double) * nodes_ > kCachedLatticeBytes;
  f_.assign(kQ * stride_, 0.0);
  next_.assign(kQ * stride_, 0.0);
  fx_.assign(nodes_, 0.0);
  fy_.assign(nodes_, 0.0);
  fz_.assign(nodes_, 0.0);
  solid_.assign(nodes_, 0);
  for (std::size_t n = 0; n < nodes_; ++n) set_equilibrium(n, params.density, Vec3::Zero());
}

void LbFluid::set_equilibrium(std::size_t node, double rho, const Vec3& u) {
  const double uu = u.squaredNorm();
  for (int i = 0; i < kQ; ++i) {
    const double cu = kC[i][0] * u.x() + kC[i][1] * u.y() + kC[i][2] * u.z();
    f_[static_cast<std::size_t>(i) * stride_ + node] = kW[i] * rho * (1.0 + cu / kCs2 + cu * cu / (2.0 * kCs2 * kCs2) - uu / (2.0 * kCs2));
  }
}

void LbFluid::use_streaming_stores(bool on) {
  if (on && dims_[0] % kLanes != 0) throw InputError("LbFluid: streaming stores need n_x to be a multiple of " + std::to_string(kLanes));
  streaming_stores_ = on;
}

void LbFluid::set_solid(std::size_t node, const Vec3& wall_velocity) {
  solid_[node] = 1;
  if (wall_velocity_.empty() && wall_velocity != Vec3::Zero()) wall_velocity_.assign(nodes_, Vec3::Zero());
  if (!wall_velocity_.empty()) wall_velocity_[node] = wall_velocity;
  for (int i = 0; i < kQ; ++i) f_[static_cast<std::size_t>(i) * stride_ + node] = 0.0;
  links_stale_ = true;
}

void LbFluid::add_force(std::size_t node, const Vec3& f) {
  fx_[node] += f.x();
  fy_[node] += f.y();
  fz_[node] += f.z();
  forces_pending_ = true;
}

Vec3 LbFluid::force_at(std::size_t node) const { return Vec3(fx_[node], fy_[node], fz_[node]) + body_force_; }

std::array<double, kQ> LbFluid::modes(std::size_t node) const {
  double n[kQ];
  for (int i = 0; i < kQ; ++i) n[i] = population(i, node);
  std::array<double, kQ> m;
  modes_of<kAllModes>(n, m.data(), std::make_integer_sequence<int, kQ>{});
  return m;
}

std::array<double, 4> LbFluid::conserved_modes(std::size_t node) const {
  double n[kQ];
  for (int i = 0; i < kQ; ++i) n[i] = population(i, node);
  std::array<double, 4> m;
  modes_of<kConservedModes>(n, m.data(), std::make_integer_sequence<int, kQ>{});
  return m;
}

double LbFluid::density(std::size_t node) const { return conserved_modes(node)[0]; }

Vec3 LbFluid::momentum_density(std::size_t node) const {
  const auto m = conserved_modes(node);
  return Vec3(m[1], m[2], m[3]);
}

Vec3 LbFluid::velocity(std::size_t node, bool with_half_force) const {
  if (solid_[node]) return wall_velocity_.empty() ? Vec3::Zero() : wall_velocity_[node];
  const auto m = conserved_modes(node);
  const Vec3 j(m[1], m[2], m[3]);
  return (with_half_force ? Vec3(j + 0.5 * force_at(node)) : j) / m[0];
}

std::pair<double, std::size_t> LbFluid::kinetic_sum() const {
  double sum = 0.0;
  std::size_t fluid = 0;
  for (std::size_t n = 0; n < nodes_; ++n) {
    if (solid_[n]) continue;
    const auto m = conserved_modes(n);
    const Vec3 u = Vec3(Vec3(m[1], m[2], m[3]) + 0.5 * force_at(n)) / m[0];
    sum += m[0] * u.squaredNorm();
    ++fluid;
  }
  return {sum, fluid};
}

Vec3 LbFluid::pending_force_total() const {
  Vec3 sum = Vec3::Zero();
  for (const std::vector<double>* component : {&fx_, &fy_, &fz_}) {
    const int k = static_cast<int>(component == &fx_ ? 0 : component == &fy_ ? 1 : 2);
    for (std::size_t n = 0; n < nodes_; ++n) sum[k] += (*component)[n];
  }
  return sum;
}

double LbFluid::total_mass() const {
  double sum = 0.0;
  for (std::size_t n = 0; n < nodes_; ++n)
    if (!solid_[n]) sum += density(n);
  return sum;
}

Vec3 LbFluid::total_momentum() const {
  Vec3 sum = Vec3::Zero();
  for (std::size_t n = 0; n < nodes_; ++n)
    if (!solid_[n]) sum += momentum_density(n);
  return sum;
}

std::vector<double> LbFluid::populations() const {
  std::vector<double> out(kQ * nodes_);
  for (int i = 0; i < kQ; ++i)
    std::copy_n(f_.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(i) * stride_), nodes_, out.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(i) * nodes_));
  return out;
}

void LbFluid::restore(const std::vector<double>& populations, std::uint64_t steps) {
  if (populations.size() != kQ * nodes_)
    throw InputError("LbFluid::restore: " + std::to_string(populations.size()) + " populations for a lattice of " + std::to_string(nodes_) + " nodes");
  for (int i = 0; i < kQ; ++i)
    std::copy_n(populations.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(i) * nodes_), nodes_, f_.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(i) * stride_));
  steps_ = steps;
}

std::vector<double> LbFluid::pending_forces() const {
  std::vector<double> out;
  out.reserve(3 * nodes_);
  for (const std::vector<double>* component : {&fx_, &fy_, &fz_}) out.insert(out.end(), component->begin(), component->begin() + static_cast<std::ptrdiff_t>(nodes_));
  return out;
}

void LbFluid::restore_pending_forces(const std::vector<double>& forces) {
  if (forces.size() != 3 * nodes_)
    throw InputError("LbFluid::restore_pending_forces: " + std::to_string(forces.size()) + " values for a lattice of " + std::to_string(nodes_) + " nodes");
  std::size_t at = 0;
  for (std::vector<double>* component : {&fx_, &fy_, &fz_})
    for (std::size_t n = 0; n < nodes_; ++n) (*component)[n] = forces[at++];
  forces_pending_ = std::any_of(forces.begin(), forces.end(), [](double f) { return f != 0.0; });
}

void LbFluid::build_links() {
  links_.clear();
  for (int z = 0; z < dims_[2]; ++z)
    for (int y = 0; y < dims_[1]; ++y)
      for (int x = 0; x < dims_[0]; ++x) {
        const std::size_t n = node(x, y, z);
        if (solid_[n]) continue;
        for (int i = 1; i < kQ; ++i) {
          const std::size_t s = node(static_cast<int>(wrap(x + kC[i][0], dims_[0])), static_cast<int>(wrap(y + kC[i][1], dims_[1])),
                                     static_cast<int>(wrap(z + kC[i][2], dims_[2])));
          if (!solid_[s]) continue;
          double term = 0.0;
          if (!wall_velocity_.empty()) {
            const Vec3& u = wall_velocity_[s];
            term = 2.0 * kW[i] * params_.density * (kC[i][0] * u.x() + kC[i][1] * u.y() + kC[i][2] * u.z()) / kCs2;
          }
          links_.push_back({n, s, i, term});
        }
      }
  links_stale_ = false;
}

// One row (fixed y, z) of nodes: the pre-collision populations in, the post-collision ones into
// out[i · stride + x] (stride: n_x rounded up to whole vectors); eight nodes at a time, the last
// vector of a row padded from a copy. Solid nodes give zeros. Thermal: with the modes' noise;
// BulkRelaxes, GhostsRelax: γ_b, γ_g ≠ 0, so that those modes are needed before the collision.
template <bool Thermal, bool BulkRelaxes, bool GhostsRelax>
void LbFluid::collide_row(std::size_t row, double* out, double* noise, std::size_t stride) const {
  constexpr ModeSet kComputed = kConservedModes | kShearModes | (BulkRelaxes ? kBulkMode : 0) | (GhostsRelax ? kGhostModes : 0);
  constexpr ModeSet kLive = kConservedModes | kBulkMode | kShearModes | (Thermal || GhostsRelax ? kGhostModes : 0);
  const int nx = dims_[0];
  const std::size_t first = row * static_cast<std::size_t>(nx);
  if constexpr (Thermal) noise_.normals(steps_, static_cast<std::uint32_t>(first), static_cast<std::size_t>(nx), kNoisyModes, noise, stride);
  for (int x = 0; x < nx; x += kLanes) {
    const int lanes = std::min(kLanes, nx - x);
    const std::size_t node = first + static_cast<std::size_t>(x);
    Lanes n[kQ], f0, f1, f2;
    std::uint64_t solid_bytes = 0;  // one byte per lane; the common all-fluid vector skips the mask
    if (lanes == kLanes) {
      // Nineteen read streams are more than the hardware prefetcher follows: fetch ahead by hand.
      for (int i = 0; i < kQ; ++i) __builtin_prefetch(f_.data() + static_cast<std::size_t>(i) * stride_ + node + kPrefetchAhead);
      for (const double* force : {fx_.data(), fy_.data(), fz_.data()}) __builtin_prefetch(force + node + kPrefetchAhead);
      __builtin_prefetch(solid_.data() + node + kPrefetchAhead);
      for (int i = 0; i < kQ; ++i) n[i] = load(f_.data() + static_cast<std::size_t>(i) * stride_ + node);
      f0 = load(fx_.data() + node), f1 = load(fy_.data() + node), f2 = load(fz_.data() + node);
      std::memcpy(&solid_bytes, solid_.data() + node, sizeof solid_bytes);
    } else {  // the row's last, partial vector: padding lanes are solid (a density of 1, no force)
      double pad[kQ + 3][kLanes] = {};
      for (int l = 0; l < lanes; ++l) {
        const std::size_t at = node + static_cast<std::size_t>(l);
        for (int i = 0; i < kQ; ++i) pad[i][l] = f_[static_cast<std::size_t>(i) * stride_ + at];
        pad[kQ][l] = fx_[at], pad[kQ + 1][l] = fy_[at], pad[kQ + 2][l] = fz_[at];
      }
      for (int i = 0; i < kQ; ++i) n[i] = load(pad[i]);
      f0 = load(pad[kQ]), f1 = load(pad[kQ + 1]), f2 = load(pad[kQ + 2]);
      for (int l = 0; l < kLanes; ++l)
        if (l >= lanes || solid_[node + static_cast<std::size_t>(l)]) solid_bytes |= std::uint64_t{1} << (8 * l);
    }
    Lanes solid = Lanes{};
    if (solid_bytes != 0)
      for (int l = 0; l < kLanes; ++l) solid[l] = static_cast<double>((solid_bytes >> (8 * l)) & 0xFF);
    f0 += body_force_.x(), f1 += body_force_.y(), f2 += body_force_.z();
    Lanes m[kQ];
    modes_of<kComputed>(n, m, std::make_integer_sequence<int, kQ>{});
    // A solid node holds no fluid: density 1 there keeps its (discarded) arithmetic finite.
    const Lanes rho = solid_bytes != 0 ? m[0] + solid : m[0];
    const Lanes inv_rho = 1.0 / rho;
    const Lanes ux = (m[1] + 0.5 * f0) * inv_rho, uy = (m[2] + 0.5 * f1) * inv_rho, uz = (m[3] + 0.5 * f2) * inv_rho;
    // Equilibrium stress modes of Π = ρ c_s² I + ρ u u (spec 40 §2.2), and the force's u f + f u.
    const Lanes pxx = rho * ux * ux, pyy = rho * uy * uy, pzz = rho * uz * uz;
    const Lanes eq[6] = {pxx + pyy + pzz, 2.0 * pxx - pyy - pzz, pyy - pzz, rho * ux * uy, rho * uy * uz, rho * uz * ux};
    const Lanes sxx = ux * f0, syy = uy * f1, szz = uz * f2;
    const Lanes force_stress[6] = {2.0 * (sxx + syy + szz), 2.0 * (2.0 * sxx - syy - szz), 2.0 * (syy - szz),
                                   ux * f1 + uy * f0, uy * f2 + uz * f1, uz * f0 + ux * f2};
    Lanes s[kQ];  // the post-collision modes
    s[0] = m[0];
    s[1] = m[1] + f0;
    s[2] = m[2] + f1;
    s[3] = m[3] + f2;
    if constexpr (BulkRelaxes) s[4] = eq[0] + gamma_[4] * (m[4] - eq[0]) + 0.5 * (1.0 + gamma_[4]) * force_stress[0];
    else s[4] = eq[0] + 0.5 * force_stress[0];
    for (int k = kFirstShearMode; k < kFirstGhostMode; ++k) {
      const int e = k - kFirstStressMode;
      s[k] = eq[e] + gamma_[k] * (m[k] - eq[e]) + 0.5 * (1.0 + gamma_[k]) * force_stress[e];
    }
    if constexpr (GhostsRelax)
      for (int k = kFirstGhostMode; k < kQ; ++k) s[k] = gamma_[k] * m[k];
    else if constexpr (Thermal)
      for (int k = kFirstGhostMode; k < kQ; ++k) s[k] = Lanes{};
    if constexpr (Thermal) {
      Lanes amplitude;
      for (int l = 0; l < kLanes; ++l) amplitude[l] = std::sqrt(std::max(rho[l], 0.0));
      for (int k = kFirstStressMode; k < kQ; ++k)
        s[k] += (amplitude * phi_[k]) * load(noise + static_cast<std::size_t>(k - kFirstStressMode) * stride + static_cast<std::size_t>(x));
    }
    for (int k = 0; k < kQ; ++k)
      if (in(kLive, k)) s[k] *= kInvB[static_cast<std::size_t>(k)];
    Lanes post[kQ];
    populations_of<kLive>(s, post, std::make_integer_sequence<int, kPairs>{});
    double* to = out + static_cast<std::size_t>(x);
    if (solid_bytes == 0)
      for (int i = 0; i < kQ; ++i) store(to + static_cast<std::size_t>(i) * stride, post[i]);
    else
      for (int i = 0; i < kQ; ++i) store(to + static_cast<std::size_t>(i) * stride, post[i] * (1.0 - solid));
  }
}

// The row's post-collision populations to their neighbours: population i of node (x, y, z) goes
// to (x, y, z) + c_i, periodically.
double* LbFluid::destination(int i, std::size_t row) {
  const int nx = dims_[0], ny = dims_[1], nz = dims_[2];
  const long y = static_cast<long>(row % static_cast<std::size_t>(ny)), z = static_cast<long>(row / static_cast<std::size_t>(ny));
  const std::size_t to_row = wrap(y + kC[i][1], ny) + static_cast<std::size_t>(ny) * wrap(z + kC[i][2], nz);
  return next_.data() + static_cast<std::size_t>(i) * stride_ + to_row * static_cast<std::size_t>(nx);
}

void LbFluid::prefetch_destinations(std::size_t row) {
  const std::size_t bytes = sizeof(double) * static_cast<std::size_t>(dims_[0]);
  for (int i = 0; i < kQ; ++i) {
    const char* dst = reinterpret_cast<const char*>(destination(i, row));
    for (std::size_t b = 0; b < bytes; b += 64) __builtin_prefetch(dst + b, 1);
  }
}

// Population i of the row's nodes, collided into out (row buffer, one halo value each side), is
// shifted along x by c_ix on the way: the destination row is written whole vectors at a time,
// aligned, and read from the buffer at x − c_ix.
void LbFluid::stream_row(std::size_t row, double* out, std::size_t stride) {
  const auto nx = static_cast<std::size_t>(dims_[0]);
  for (int i = 0; i < kQ; ++i) {
    double* src = out + static_cast<std::size_t>(i) * stride;
    src[-1] = src[nx - 1], src[nx] = src[0];  // periodic in x
    src -= kC[i][0];
    double* dst = destination(i, row);
    if (streaming_stores_) {
      for (std::size_t x = 0; x < nx; x += kLanes) store_streaming(dst + x, load(src + x));
    } else {
      std::memcpy(dst, src, sizeof(double) * nx);
    }
  }
}

void LbFluid::clear_row_forces(std::size_t row) {
  const auto nx = static_cast<std::size_t>(dims_[0]);
  for (std::vector<double>* component : {&fx_, &fy_, &fz_}) std::fill_n(component->begin() + static_cast<std::ptrdiff_t>(row * nx), nx, 0.0);
}

LbFluid::RowCollision LbFluid::row_collision() const {
  const bool thermal = params_.kT > 0.0, bulk = gamma_[kFirstStressMode] != 0.0, ghosts = gamma_[kFirstGhostMode] != 0.0;
  constexpr RowCollision kTable[2][2][2] = {
      {{&LbFluid::collide_row<false, false, false>, &LbFluid::collide_row<false, false, true>},
       {&LbFluid::collide_row<false, true, false>, &LbFluid::collide_row<false, true, true>}},
      {{&LbFluid::collide_row<true, false, false>, &LbFluid::collide_row<true, false, true>},
       {&LbFluid::collide_row<true, true, false>, &LbFluid::collide_row<true, true, true>}}};
  return kTable[thermal][bulk][ghosts];
}

void LbFluid::step() {
  if (links_stale_) build_links();
  const std::size_t rows = static_cast<std::size_t>(dims_[1]) * static_cast<std::size_t>(dims_[2]);
  // A row buffer holds each population's row, whole vectors, and a vector's gap before the next
  // for the periodic halo (stream_row).
  const std::size_t stride = (static_cast<std::size_t>(dims_[0]) + kLanes - 1) / kLanes * kLanes + kLanes;
  const auto collide = row_collision();
#pragma omp parallel if (nodes_ >= kParallelNodes)
  {
    // Each thread's row buffers, kept from step to step.
    static thread_local std::vector<double> out, noise;
    out.resize(kQ * stride + 2 * kLanes);
    noise.resize(params_.kT > 0.0 ? kNoisyModes * stride : 0);
#pragma omp for schedule(static) nowait
    for (std::size_t row = 0; row < rows; ++row) {
      if (!streaming_stores_ && row + 1 < rows) prefetch_destinations(row + 1);
      (this->*collide)(row, out.data() + kLanes, noise.data(), stride);
      stream_row(row, out.data() + kLanes, stride);
      if (forces_pending_) clear_row_forces(row);  // while its lines are still in the cache
    }
    if (streaming_stores_) fence_streaming_stores();  // the rows visible before another thread reads them
#pragma omp barrier
    // Halfway bounce-back: what a fluid node sent into a solid one comes back reversed.
#pragma omp for schedule(static)
    for (std::size_t l = 0; l < links_.size(); ++l) {
      const BoundaryLink& link = links_[l];
      const int back = opposite(link.i);
      next_[static_cast<std::size_t>(back) * stride_ + link.fluid] = next_[static_cast<std::size_t>(link.i) * stride_ + link.solid] - link.wall_term;
    }
  }
  forces_pending_ = false;
  std::swap(f_, next_);
  ++steps_;
}

}  // namespace anisodyn::lb

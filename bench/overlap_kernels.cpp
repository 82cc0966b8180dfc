// Overlap-kernel micro-benchmarks (docs/geometry.md has the measured numbers).
//
// (1) Cuboid–sphere, following the OCSI benchmark protocol of spec 10 §2.5: for each (L*, W*, R*)
//     (T = 1), 3 independent sets of N_c = 2×10⁶ configurations with the sphere centre uniform in
//     the spherocuboid of radius R_sc chosen so that 40% are non-overlapping, each configuration
//     rotated by its own uniform random rotation. Only the loop of checks is timed; one benchmark
//     iteration checks all 3 sets, so the time is the mean over the sets. Kernels on the same data:
//       OCSI (float, and double on double data), Arvo, QRI, QRF (quick rejection), and "Signed"
//       (the portable equivalent of the SSE-intr variant: l = min(a + c, 0) + max(a − c, 0)).
//     Two layouts: AoS (one 48-byte record of 9 axis components + 3 position components per
//     configuration) and SoA (12 separate arrays). Mismatches against OCSI are counted while the data
//     are built and reported as the counter `mismatch` (expected 0).
//     The 2×10⁶-configuration sets do not fit in cache, so these runs are bounded by memory
//     bandwidth; the `Hot` variants repeat the same kernels on the first 131072 configurations of
//     set 0 (L3-resident), which is closer to an MC sweep (particle data in cache) and measures the
//     kernel itself. The hot set is deliberately large: replaying a few thousand configurations
//     lets the branch predictor learn the outcomes, which flatters the branchy QRI/QRF/Arvo.
// (2) Cuboid–cuboid SAT on boards 1×√12×12 and unit cubes: independent uniform orientations,
//     centre distance uniform in [0, sum of circumradii] (the pairs a cell list hands to the test),
//     65536 precomputed pairs cycled; the engine kernel (all 15 axes, no branches) and an early-exit
//     variant, both called out of line as from the MC loop. Also spherocylinder pairs, cuboid–sphere
//     in double through the Eigen interface, and the generic dispatcher.
// Counters: ns_per_check (time per check), ms_per_2e6 (spec §2.5 unit), overlap_frac.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "anisodyn/core/quaternion.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/geometry/cuboid_cuboid.hpp"
#include "anisodyn/geometry/cuboid_sphere.hpp"
#include "anisodyn/geometry/overlap.hpp"
#include "anisodyn/geometry/spherocylinder.hpp"

using namespace anisodyn;

namespace {

// ---- alternative cuboid–sphere tests (spec §2.2 "reference algorithms"), benchmark-only -----------
// All take the axes (column-major, axes[3k + i] = component i of ê_k), half-extents c, the sphere
// centre relative to the cuboid centre r, and the radius R.

template <typename Real>
inline Real project(const Real* axes, const Real* r, int k) {
  return axes[3 * k] * r[0] + axes[3 * k + 1] * r[1] + axes[3 * k + 2] * r[2];
}

/// Arvo (1990): centre in the box frame, box [−c, c], branch per axis.
template <typename Real>
inline bool arvo(const Real* axes, const Real* c, const Real* r, Real R) {
  Real d = 0;
  for (int k = 0; k < 3; ++k) {
    const Real s = project(axes, r, k);
    if (s < -c[k]) {
      const Real e = -c[k] - s;
      d += e * e;
    } else if (s > c[k]) {
      const Real e = s - c[k];
      d += e * e;
    }
  }
  return d <= R * R;
}

/// QRI, quick rejection intertwined (Larsson, Akenine-Möller & Lengyel 2007).
template <typename Real>
inline bool qri(const Real* axes, const Real* c, const Real* r, Real R) {
  Real d = 0;
  for (int k = 0; k < 3; ++k) {
    const Real a = project(axes, r, k);
    Real l = a + c[k];
    if (l < 0) {
      if (l < -R) return false;
      d += l * l;
    } else {
      l = a - c[k];
      if (l > 0) {
        if (l > R) return false;
        d += l * l;
      }
    }
  }
  return d <= R * R;
}

/// QRF, quick rejection first.
template <typename Real>
inline bool qrf(const Real* axes, const Real* c, const Real* r, Real R) {
  Real a[3];
  for (int k = 0; k < 3; ++k) {
    a[k] = project(axes, r, k);
    if (a[k] < -c[k] - R || a[k] > c[k] + R) return false;
  }
  Real d = 0;
  for (int k = 0; k < 3; ++k) {
    if (a[k] < -c[k]) {
      const Real e = a[k] + c[k];
      d += e * e;
    } else if (a[k] > c[k]) {
      const Real e = a[k] - c[k];
      d += e * e;
    }
  }
  return d <= R * R;
}

/// Signed, branch-free Arvo (the SSE-intr variant without intrinsics).
template <typename Real>
inline bool signed_minmax(const Real* axes, const Real* c, const Real* r, Real R) {
  Real d = 0;
  for (int k = 0; k < 3; ++k) {
    const Real a = project(axes, r, k);
    // min(x, 0) = (x − |x|)/2 and max(x, 0) = (x + |x|)/2: exact and free of branches (GCC compiles
    // std::min/std::max followed by a square into conditional jumps).
    const Real lo = a + c[k], hi = a - c[k];
    const Real l = Real(0.5) * ((lo - std::abs(lo)) + (hi + std::abs(hi)));
    d += l * l;
  }
  return d <= R * R;
}

template <typename Real>
inline bool ocsi(const Real* axes, const Real* c, const Real* r, Real R) {
  return overlap_cuboid_sphere<Real>(axes, c, r, R);
}

// ---- early-exit SAT, for comparison with the engine kernel (which evaluates all 15 axes) --------
// Same pre-checks, tests and ε as overlap_cuboid_cuboid, but returning at the first separating axis
// (face axes first).
inline bool sat_early_exit(const Vec3& a, const Mat3& Ra, const Vec3& b, const Mat3& Rb, const Vec3& t) {
  const double t2 = t.squaredNorm();
  const double ra2 = a.squaredNorm(), rb2 = b.squaredNorm();
  const double x = t2 - ra2 - rb2;
  if ((x > 0.0) & (x * x > 4.0 * (1.0 + 1e-12) * ra2 * rb2)) return false;
  const double rin = std::min({a[0], a[1], a[2]}) + std::min({b[0], b[1], b[2]});
  if (t2 <= (1.0 - 1e-12) * rin * rin) return true;
  const double eps = kSatEpsilon * std::max({a[0], a[1], a[2], b[0], b[1], b[2]});
  double R[3][3], AR[3][3], tA[3];
  for (int k = 0; k < 3; ++k) {
    tA[k] = Ra(0, k) * t[0] + Ra(1, k) * t[1] + Ra(2, k) * t[2];
    for (int l = 0; l < 3; ++l) {
      R[k][l] = Ra(0, k) * Rb(0, l) + Ra(1, k) * Rb(1, l) + Ra(2, k) * Rb(2, l);
      AR[k][l] = std::abs(R[k][l]) + eps;
    }
  }
  for (int k = 0; k < 3; ++k)
    if (std::abs(tA[k]) > a[k] + b[0] * AR[k][0] + b[1] * AR[k][1] + b[2] * AR[k][2]) return false;
  for (int l = 0; l < 3; ++l) {
    const double tB = tA[0] * R[0][l] + tA[1] * R[1][l] + tA[2] * R[2][l];
    if (std::abs(tB) > a[0] * AR[0][l] + a[1] * AR[1][l] + a[2] * AR[2][l] + b[l]) return false;
  }
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    for (int l = 0; l < 3; ++l) {
      const int l1 = (l + 1) % 3, l2 = (l + 2) % 3;
      const double lhs = std::abs(tA[k2] * R[k1][l] - tA[k1] * R[k2][l]);
      const double rhs = a[k1] * AR[k2][l] + a[k2] * AR[k1][l] + b[l1] * AR[k][l2] + b[l2] * AR[k][l1];
      if (lhs > rhs) return false;
    }
  }
  return true;
}

// Out-of-line entry points, so that both SAT variants are timed as a call per pair (as from the MC
// loop) and neither benefits from hoisting the shape-dependent set-up out of the benchmark loop.
[[gnu::noinline]] bool sat_engine_call(const Vec3& a, const Mat3& Ra, const Vec3& b, const Mat3& Rb, const Vec3& t) {
  return overlap_cuboid_cuboid(a, Ra, b, Rb, t);
}
[[gnu::noinline]] bool sat_early_exit_call(const Vec3& a, const Mat3& Ra, const Vec3& b, const Mat3& Rb,
                                           const Vec3& t) {
  return sat_early_exit(a, Ra, b, Rb, t);
}

// ---- OCSI protocol data -----------------------------------------------------------------------

struct Geometry {
  double L, W, R;  // L*, W*, R* (T = 1)
};

const Geometry kGeometries[] = {
    {1, 1, 0.05},
    {12, std::sqrt(12.0), 0.05},
    {12, std::sqrt(12.0), 0.5},
    {12, std::sqrt(12.0), 5},
    {3, 5, 5},
    {7, 8, 5},
    {20, 20, 5},
};

constexpr std::size_t kConfigs = 2'000'000;  // N_c per set
constexpr int kSets = 3;
constexpr std::size_t kHot = 131072;  // 6.3 MB float / 12.6 MB double AoS: L3-resident

double dilated_volume(double a, double b, double c, double r) {
  return 8 * a * b * c + 8 * r * (a * b + b * c + c * a) + 2 * M_PI * r * r * (a + b + c) +
         4.0 / 3.0 * M_PI * r * r * r;
}

template <typename Real>
struct SoA {
  std::vector<Real> v[12];  // 9 axis components (column-major), then the 3 position components
  void resize(std::size_t n) {
    for (auto& x : v) x.resize(n);
  }
};

struct ProtocolData {
  int geometry = -1;
  float half_f[3];
  double half_d[3];
  float R_f;
  double R_d, R_sc;
  std::vector<float> aos_f[kSets];   // 12 floats per configuration
  std::vector<double> aos_d[kSets];  // 12 doubles per configuration
  SoA<float> soa_f[kSets];
  double overlap_fraction = 0;
  std::int64_t mismatches[5] = {0, 0, 0, 0, 0};  // Arvo, QRI, QRF, Signed, OCSI-double vs OCSI-float
};

ProtocolData& protocol_data(int geometry) {
  static ProtocolData d;
  if (d.geometry == geometry) return d;
  d.geometry = geometry;
  const Geometry g = kGeometries[geometry];
  const double half[3] = {0.5, 0.5 * g.W, 0.5 * g.L};
  // R_sc by bisection: V(R) / V(R_sc) = 0.6.
  const double target = dilated_volume(half[0], half[1], half[2], g.R) / 0.6;
  double lo = g.R, hi = g.R + 100;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (dilated_volume(half[0], half[1], half[2], mid) < target ? lo : hi) = mid;
  }
  d.R_sc = 0.5 * (lo + hi);
  d.R_d = g.R;
  d.R_f = static_cast<float>(g.R);
  for (int k = 0; k < 3; ++k) {
    d.half_d[k] = half[k];
    d.half_f[k] = static_cast<float>(half[k]);
  }
  std::int64_t overlapping = 0;
  for (auto& m : d.mismatches) m = 0;
  for (int s = 0; s < kSets; ++s) {
    Rng rng(2021, static_cast<std::uint64_t>(100 * geometry + s));
    auto& af = d.aos_f[s];
    auto& ad = d.aos_d[s];
    af.resize(12 * kConfigs);
    ad.resize(12 * kConfigs);
    d.soa_f[s].resize(kConfigs);
    for (std::size_t i = 0; i < kConfigs; ++i) {
      // 1-2: axis-aligned cuboid at the origin, centre uniform in the spherocuboid (rejection).
      Vec3 p;
      for (;;) {
        double dmin2 = 0;
        for (int k = 0; k < 3; ++k) {
          p[k] = rng.uniform(-(half[k] + d.R_sc), half[k] + d.R_sc);
          const double e = std::max(std::abs(p[k]) - half[k], 0.0);
          dmin2 += e * e;
        }
        if (dmin2 <= d.R_sc * d.R_sc) break;
      }
      // 3: one uniform random rotation of the whole configuration.
      const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
      const Mat3 Q = uniform_quaternion(u1, u2, u3).toRotationMatrix();
      const Vec3 r = Q * p;
      for (int j = 0; j < 9; ++j) {
        ad[12 * i + j] = Q.data()[j];
        af[12 * i + j] = static_cast<float>(Q.data()[j]);
      }
      for (int k = 0; k < 3; ++k) {
        ad[12 * i + 9 + k] = r[k];
        af[12 * i + 9 + k] = static_cast<float>(r[k]);
      }
      for (int j = 0; j < 12; ++j) d.soa_f[s].v[j][i] = af[12 * i + j];
      const float* e = &af[12 * i];
      const float* rf = e + 9;
      const bool o = ocsi<float>(e, d.half_f, rf, d.R_f);
      overlapping += o;
      d.mismatches[0] += arvo<float>(e, d.half_f, rf, d.R_f) != o;
      d.mismatches[1] += qri<float>(e, d.half_f, rf, d.R_f) != o;
      d.mismatches[2] += qrf<float>(e, d.half_f, rf, d.R_f) != o;
      d.mismatches[3] += signed_minmax<float>(e, d.half_f, rf, d.R_f) != o;
      d.mismatches[4] += ocsi<double>(&ad[12 * i], d.half_d, &ad[12 * i + 9], d.R_d) != o;
    }
  }
  d.overlap_fraction = double(overlapping) / double(kSets * kConfigs);
  return d;
}

enum class Kernel { OcsiFloat, OcsiDouble, Arvo, Qri, Qrf, Signed };
const char* kernel_name(Kernel k) {
  switch (k) {
    case Kernel::OcsiFloat:
      return "OCSI_float";
    case Kernel::OcsiDouble:
      return "OCSI_double";
    case Kernel::Arvo:
      return "Arvo_float";
    case Kernel::Qri:
      return "QRI_float";
    case Kernel::Qrf:
      return "QRF_float";
    case Kernel::Signed:
      return "Signed_float";
  }
  return "?";
}

template <typename Real, bool (*F)(const Real*, const Real*, const Real*, Real)>
std::int64_t count_aos(const Real* data, std::size_t n, const Real* half, Real R) {
  std::int64_t count = 0;
  for (std::size_t i = 0; i < n; ++i) count += F(data + 12 * i, half, data + 12 * i + 9, R);
  return count;
}

template <bool (*F)(const float*, const float*, const float*, float)>
std::int64_t count_soa(const SoA<float>& s, std::size_t n, const float* half, float R) {
  const float* v[12];
  for (int j = 0; j < 12; ++j) v[j] = s.v[j].data();
  std::int64_t count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const float e[9] = {v[0][i], v[1][i], v[2][i], v[3][i], v[4][i], v[5][i], v[6][i], v[7][i], v[8][i]};
    const float r[3] = {v[9][i], v[10][i], v[11][i]};
    count += F(e, half, r, R);
  }
  return count;
}

std::int64_t run_aos(Kernel k, const ProtocolData& d, int set, std::size_t n) {
  const float* f = d.aos_f[set].data();
  switch (k) {
    case Kernel::OcsiFloat:
      return count_aos<float, ocsi<float>>(f, n, d.half_f, d.R_f);
    case Kernel::OcsiDouble:
      return count_aos<double, ocsi<double>>(d.aos_d[set].data(), n, d.half_d, d.R_d);
    case Kernel::Arvo:
      return count_aos<float, arvo<float>>(f, n, d.half_f, d.R_f);
    case Kernel::Qri:
      return count_aos<float, qri<float>>(f, n, d.half_f, d.R_f);
    case Kernel::Qrf:
      return count_aos<float, qrf<float>>(f, n, d.half_f, d.R_f);
    case Kernel::Signed:
      return count_aos<float, signed_minmax<float>>(f, n, d.half_f, d.R_f);
  }
  return 0;
}

std::int64_t run_soa(Kernel k, const ProtocolData& d, int set, std::size_t n) {
  const SoA<float>& s = d.soa_f[set];
  switch (k) {
    case Kernel::OcsiFloat:
      return count_soa<ocsi<float>>(s, n, d.half_f, d.R_f);
    case Kernel::Arvo:
      return count_soa<arvo<float>>(s, n, d.half_f, d.R_f);
    case Kernel::Qri:
      return count_soa<qri<float>>(s, n, d.half_f, d.R_f);
    case Kernel::Qrf:
      return count_soa<qrf<float>>(s, n, d.half_f, d.R_f);
    case Kernel::Signed:
      return count_soa<signed_minmax<float>>(s, n, d.half_f, d.R_f);
    case Kernel::OcsiDouble:
      break;
  }
  return 0;
}

void set_check_counters(benchmark::State& state, double checks_per_iteration) {
  const double checks = checks_per_iteration * double(state.iterations());
  state.counters["ns_per_check"] =
      benchmark::Counter(checks * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["ms_per_2e6"] =
      benchmark::Counter(checks / 2e6 * 1e-3, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

/// layout: 0 = AoS, 1 = SoA; hot: 4096 configurations of set 0 repeated (cache-resident).
void bm_ocsi_protocol(benchmark::State& state, int geometry, Kernel kernel, int layout, bool hot) {
  const ProtocolData& d = protocol_data(geometry);
  std::int64_t total = 0;
  double checks_per_iteration = 0;
  for (auto _ : state) {
    std::int64_t count = 0;
    if (hot) {
      for (int rep = 0; rep < 4; ++rep)
        count += layout == 0 ? run_aos(kernel, d, 0, kHot) : run_soa(kernel, d, 0, kHot);
      checks_per_iteration = 4.0 * kHot;
    } else {
      for (int s = 0; s < kSets; ++s)
        count += layout == 0 ? run_aos(kernel, d, s, kConfigs) : run_soa(kernel, d, s, kConfigs);
      checks_per_iteration = double(kSets) * kConfigs;
    }
    benchmark::DoNotOptimize(count);
    total += count;
  }
  set_check_counters(state, checks_per_iteration);
  state.counters["overlap_frac"] = double(total) / (checks_per_iteration * double(state.iterations()));
  state.counters["spherocuboid_overlap_frac"] = d.overlap_fraction;
  const int mi = kernel == Kernel::Arvo         ? 0
                 : kernel == Kernel::Qri        ? 1
                 : kernel == Kernel::Qrf        ? 2
                 : kernel == Kernel::Signed     ? 3
                 : kernel == Kernel::OcsiDouble ? 4
                                                : -1;
  state.counters["mismatch"] = mi < 0 ? 0.0 : double(d.mismatches[mi]);
}

// ---- pair benchmarks (SAT, spherocylinders, dispatcher) -------------------------------------------

struct PairData {
  Shape a, b;
  std::vector<Mat3> Ra, Rb;
  std::vector<Vec3> t;
};

constexpr std::size_t kPairs = 1 << 16;

PairData make_pairs(const Shape& a, const Shape& b, std::uint64_t seed) {
  PairData p{a, b, {}, {}, {}};
  Rng rng(seed, 0);
  const double rmax = a.circumradius() + b.circumradius();
  for (std::size_t i = 0; i < kPairs; ++i) {
    for (auto* R : {&p.Ra, &p.Rb}) {
      const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
      R->push_back(uniform_quaternion(u1, u2, u3).toRotationMatrix());
    }
    const double z = rng.uniform(-1, 1), phi = 2 * M_PI * rng.uniform(), s = std::sqrt(1 - z * z);
    p.t.push_back(rmax * rng.uniform() * Vec3(s * std::cos(phi), s * std::sin(phi), z));
  }
  return p;
}

template <typename F>
void bm_pairs(benchmark::State& state, const PairData& p, F&& test) {
  std::int64_t total = 0;
  for (auto _ : state) {
    std::int64_t count = 0;
    for (std::size_t i = 0; i < kPairs; ++i) count += test(p, i);
    benchmark::DoNotOptimize(count);
    total += count;
  }
  set_check_counters(state, double(kPairs));
  state.counters["overlap_frac"] = double(total) / (double(kPairs) * double(state.iterations()));
}

const PairData& boards() {
  static const PairData p = make_pairs(Shape::cuboid(1, std::sqrt(12.0), 12), Shape::cuboid(1, std::sqrt(12.0), 12), 1);
  return p;
}
const PairData& cubes() {
  static const PairData p = make_pairs(Shape::cuboid(1, 1, 1), Shape::cuboid(1, 1, 1), 2);
  return p;
}
const PairData& rods() {
  static const PairData p = make_pairs(Shape::spherocylinder(9, 1), Shape::spherocylinder(9, 1), 3);
  return p;
}
const PairData& rod_sphere() {
  static const PairData p = make_pairs(Shape::spherocylinder(9, 1), Shape::sphere(1), 4);
  return p;
}
const PairData& board_sphere() {
  static const PairData p = make_pairs(Shape::cuboid(1, std::sqrt(12.0), 12), Shape::sphere(1), 5);
  return p;
}

void register_all() {
  const Kernel kernels[] = {Kernel::OcsiFloat, Kernel::OcsiDouble, Kernel::Arvo,
                            Kernel::Qri,       Kernel::Qrf,        Kernel::Signed};
  for (int g = 0; g < static_cast<int>(std::size(kGeometries)); ++g) {
    char geo[64];
    std::snprintf(geo, sizeof geo, "L%g_W%.3g_R%g", kGeometries[g].L, kGeometries[g].W, kGeometries[g].R);
    for (bool hot : {false, true})
      for (int layout : {0, 1})
        for (Kernel k : kernels) {
          if (layout == 1 && k == Kernel::OcsiDouble) continue;
          const std::string name = std::string("CuboidSphere/") + (hot ? "Hot/" : "Protocol/") +
                                   (layout == 0 ? "AoS/" : "SoA/") + kernel_name(k) + "/" + geo;
          benchmark::RegisterBenchmark(name.c_str(),
                                       [=](benchmark::State& st) { bm_ocsi_protocol(st, g, k, layout, hot); })
              ->Unit(benchmark::kMillisecond)
              ->MinTime(hot ? 0.2 : 0.5);
        }
  }
  const auto sat = [](const PairData& p, std::size_t i) {
    return sat_engine_call(p.a.half_extents(), p.Ra[i], p.b.half_extents(), p.Rb[i], p.t[i]);
  };
  const auto sat_ee = [](const PairData& p, std::size_t i) {
    return sat_early_exit_call(p.a.half_extents(), p.Ra[i], p.b.half_extents(), p.Rb[i], p.t[i]);
  };
  const auto generic = [](const PairData& p, std::size_t i) { return overlap(p.a, p.Ra[i], p.b, p.Rb[i], p.t[i]); };
  const auto scsc = [](const PairData& p, std::size_t i) {
    return overlap_spherocylinder_spherocylinder(0.5 * p.a.length, 0.5 * p.a.diameter, p.Ra[i].col(2), 0.5 * p.b.length,
                                                 0.5 * p.b.diameter, p.Rb[i].col(2), p.t[i]);
  };
  const auto scs = [](const PairData& p, std::size_t i) {
    return overlap_spherocylinder_sphere(0.5 * p.a.length, 0.5 * p.a.diameter, p.Ra[i].col(2), 0.5 * p.b.diameter,
                                         p.t[i]);
  };
  const auto cs = [](const PairData& p, std::size_t i) {
    return overlap_cuboid_sphere(p.Ra[i], p.a.half_extents(), p.t[i], 0.5 * p.b.diameter);
  };
  benchmark::RegisterBenchmark("Pairs/CuboidCuboid_SAT/board_1x3.46x12",
                               [=](benchmark::State& st) { bm_pairs(st, boards(), sat); });
  benchmark::RegisterBenchmark("Pairs/CuboidCuboid_SAT/unit_cube",
                               [=](benchmark::State& st) { bm_pairs(st, cubes(), sat); });
  benchmark::RegisterBenchmark("Pairs/CuboidCuboid_SAT_early_exit/board_1x3.46x12",
                               [=](benchmark::State& st) { bm_pairs(st, boards(), sat_ee); });
  benchmark::RegisterBenchmark("Pairs/CuboidCuboid_SAT_early_exit/unit_cube",
                               [=](benchmark::State& st) { bm_pairs(st, cubes(), sat_ee); });
  benchmark::RegisterBenchmark("Pairs/Dispatcher/board_1x3.46x12",
                               [=](benchmark::State& st) { bm_pairs(st, boards(), generic); });
  benchmark::RegisterBenchmark("Pairs/CuboidSphere_OCSI_double_Eigen/board_sphere1",
                               [=](benchmark::State& st) { bm_pairs(st, board_sphere(), cs); });
  benchmark::RegisterBenchmark("Pairs/Spherocylinder_pair/L9_D1",
                               [=](benchmark::State& st) { bm_pairs(st, rods(), scsc); });
  benchmark::RegisterBenchmark("Pairs/Spherocylinder_sphere/L9_D1_d1",
                               [=](benchmark::State& st) { bm_pairs(st, rod_sphere(), scs); });
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

// Dipolar Ewald cost per trial move (docs/ewald.md has the measured numbers).
//
// Systems (spec 10 §6: unit cubes at packing fraction η = 0.02, every cube carries a dipole):
//   N = 1500 in a cubic box of edge 42.17σ, and N = 125 in 18.42σ; parameters from
//   choose_ewald_parameters(·, N, 1e-5) (the default accuracy) unless the name says otherwise.
// Positions: uniform random with centre distances ≥ 1.1σ (fixed seed). Trial moves: a random
// particle displaced uniformly in [−0.1, 0.1]³ and wrapped, 4096 precomputed moves cycled, so
// the RNG is not timed.
//   Delta/<N>/<a>    delta_energy only (the MC trial: move rejected or not yet decided), at
//                    accuracy 10^−a (a = 5: the default);
//   DeltaAccept/<N>  delta_energy + accept + position update on every move (upper bound of an
//                    accepted move);
//   RealErfc/<N>     the same real-space sum written naively with std::erfc/std::exp and a
//                    branch on r < r_cut (for comparison with the polynomial kernel);
//   Bare/<N>         minimum_image_only smoke-test mode;
//   Rebuild/<N>, Total/<N>  S(k) from scratch and the full energy (not in the inner loop).
//   Accuracy/<N>/<fluid|strings>  (one iteration, not a timing) ΔU of 500 trial moves with the
//                    default parameters against accuracy 1e-11 parameters, in k_BT at γ = 13:
//                    counters small_rms/small_max (moves of ±0.1σ per axis, as in the DMC) and
//                    far_rms/far_max (to a random point of the box, no overlap check), and
//                    total_err_per_dipole (|ΔU_total|/N). "strings": chains of 10 cubes at contact
//                    along the field (the field-on structure), placed at random without overlap.
// Counters: n_k (half-space wave vectors), kappa, n_max; the time column is the time per call.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "anisodyn/core/box.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/interactions/dipolar_ewald.hpp"

using namespace anisodyn;

namespace {

struct Setup {
  Vec3 L;
  Particles p;
  std::vector<char> dip;
  std::vector<std::size_t> idx;
  std::vector<Vec3> target;
  std::vector<Vec3> disp;
};

Setup make_setup(std::size_t n, bool strings = false) {
  Setup s;
  const double edge = n == 1500 ? 42.17 : 18.42;
  s.L = Vec3(edge, edge, edge);
  const Box box(s.L);
  Rng rng(20240611, n);
  auto free_at = [&](const Vec3& r, double d2) {
    for (std::size_t j = 0; j < s.p.size(); ++j)
      if (box.min_image(r - s.p.position(j)).squaredNorm() < d2) return false;
    return true;
  };
  while (s.p.size() < n) {
    Vec3 r(rng.uniform(0, edge), rng.uniform(0, edge), rng.uniform(0, edge));
    const std::size_t len = strings ? std::min<std::size_t>(10, n - s.p.size()) : 1;
    bool ok = true;
    for (std::size_t k = 0; k < len && ok; ++k) ok = free_at(r + Vec3(0, 0, static_cast<double>(k)), 1.21);
    if (!ok) continue;
    for (std::size_t k = 0; k < len; ++k) {
      Vec3 q = r + Vec3(0, 0, static_cast<double>(k));
      Int3 img(0, 0, 0);
      box.wrap(q, img);
      s.p.add(0, q, Quat::Identity(), static_cast<std::int64_t>(s.p.size()));
    }
  }
  s.dip.assign(n, 1);
  for (int m = 0; m < 4096; ++m) {
    const std::size_t i = rng.index(n);
    const Vec3 d(rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1));
    Vec3 r = s.p.position(i) + d;
    Int3 img(0, 0, 0);
    box.wrap(r, img);
    s.idx.push_back(i);
    s.target.push_back(r);
    s.disp.push_back(d);
  }
  return s;
}

void set_counters(benchmark::State& state, const DipolarEwald& ew) {
  state.counters["n_k"] = static_cast<double>(ew.wave_vector_count());
  state.counters["kappa"] = ew.parameters().kappa;
  state.counters["n_max"] = ew.parameters().n_max;
}

void BM_Delta(benchmark::State& state) {
  Setup s = make_setup(static_cast<std::size_t>(state.range(0)));
  const double accuracy = std::pow(10.0, -static_cast<double>(state.range(1)));
  DipolarEwald ew(s.L, Vec3::UnitZ(), 13.0, choose_ewald_parameters(s.L, s.p.size(), accuracy), s.dip);
  ew.rebuild(s.p);
  std::size_t m = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(ew.delta_energy(s.p, s.idx[m], s.target[m]));
    m = (m + 1) & 4095;
  }
  set_counters(state, ew);
}

void BM_DeltaAccept(benchmark::State& state) {
  Setup s = make_setup(static_cast<std::size_t>(state.range(0)));
  DipolarEwald ew(s.L, Vec3::UnitZ(), 13.0, choose_ewald_parameters(s.L, s.p.size(), 1e-5), s.dip);
  ew.rebuild(s.p);
  const Box box(s.L);
  std::size_t m = 0;
  for (auto _ : state) {
    const std::size_t i = s.idx[m];
    Vec3 r = s.p.position(i) + s.disp[m];  // the precomputed targets go stale once particles move
    Int3 img(0, 0, 0);
    box.wrap(r, img);
    benchmark::DoNotOptimize(ew.delta_energy(s.p, i, r));
    ew.accept(i);
    s.p.set_position(i, r);
    m = (m + 1) & 4095;
  }
  set_counters(state, ew);
}

/// Naive real-space ΔU with std::erfc (comparison only; same cut-off and minimum image).
double naive_real_delta(const Particles& p, std::size_t i, const Vec3& rn, const Vec3& L, const Vec3& e,
                        double kappa, double rc) {
  const Box box(L);
  const double tsp = 2.0 / std::sqrt(M_PI);
  auto psi = [&](const Vec3& d0) {
    const Vec3 d = box.min_image(d0);
    const double s = d.squaredNorm();
    if (s >= rc * rc) return 0.0;
    const double r = std::sqrt(s), x = kappa * r, ex = std::exp(-x * x), ec = std::erfc(x);
    const double B = ec / (s * r) + tsp * kappa * ex / s;
    const double C = 3 * ec / (s * s * r) + tsp * kappa * (2 * kappa * kappa + 3 / s) * ex / s;
    const double ed = e.dot(d);
    return B - ed * ed * C;
  };
  const Vec3 ro = p.position(i);
  double sum = 0;
  for (std::size_t j = 0; j < p.size(); ++j) {
    if (j == i) continue;
    const Vec3 rj = p.position(j);
    sum += psi(rn - rj) - psi(ro - rj);
  }
  return sum;
}

void BM_RealErfc(benchmark::State& state) {
  Setup s = make_setup(static_cast<std::size_t>(state.range(0)));
  const EwaldParameters ep = choose_ewald_parameters(s.L, s.p.size(), 1e-5);
  DipolarEwald ew(s.L, Vec3::UnitZ(), 13.0, ep, s.dip);
  std::size_t m = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(naive_real_delta(s.p, s.idx[m], s.target[m], s.L, Vec3::UnitZ(), ep.kappa, ep.r_cut));
    m = (m + 1) & 4095;
  }
  set_counters(state, ew);
}

void BM_Bare(benchmark::State& state) {
  Setup s = make_setup(static_cast<std::size_t>(state.range(0)));
  EwaldParameters ep;
  ep.minimum_image_only = true;
  DipolarEwald ew(s.L, Vec3::UnitZ(), 13.0, ep, s.dip);
  std::size_t m = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(ew.delta_energy(s.p, s.idx[m], s.target[m]));
    m = (m + 1) & 4095;
  }
  set_counters(state, ew);
}

void BM_Rebuild(benchmark::State& state) {
  Setup s = make_setup(static_cast<std::size_t>(state.range(0)));
  DipolarEwald ew(s.L, Vec3::UnitZ(), 13.0, choose_ewald_parameters(s.L, s.p.size(), 1e-5), s.dip);
  for (auto _ : state) ew.rebuild(s.p);
  set_counters(state, ew);
}

void BM_Total(benchmark::State& state) {
  Setup s = make_setup(static_cast<std::size_t>(state.range(0)));
  DipolarEwald ew(s.L, Vec3::UnitZ(), 13.0, choose_ewald_parameters(s.L, s.p.size(), 1e-5), s.dip);
  for (auto _ : state) benchmark::DoNotOptimize(ew.total_energy(s.p));
  set_counters(state, ew);
}

void BM_Accuracy(benchmark::State& state) {
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  Setup s = make_setup(n, state.range(1) != 0);
  DipolarEwald ew(s.L, Vec3::UnitZ(), 13.0, choose_ewald_parameters(s.L, n, 1e-5), s.dip);
  DipolarEwald ref(s.L, Vec3::UnitZ(), 13.0, choose_ewald_parameters(s.L, n, 1e-11), s.dip);
  ew.rebuild(s.p);
  ref.rebuild(s.p);
  const Box box(s.L);
  double small2 = 0, small_max = 0, far2 = 0, far_max = 0, total_err = 0;
  for (auto _ : state) {
    Rng rng(99, n);
    const int moves = 500;
    for (int m = 0; m < moves; ++m) {
      const std::size_t i = rng.index(n);
      Vec3 r = s.p.position(i) + Vec3(rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1));
      Int3 img(0, 0, 0);
      box.wrap(r, img);
      double e = std::fabs(ew.delta_energy(s.p, i, r) - ref.delta_energy(s.p, i, r));
      small2 += e * e;
      small_max = std::max(small_max, e);
      const Vec3 far(rng.uniform(0, s.L.x()), rng.uniform(0, s.L.y()), rng.uniform(0, s.L.z()));
      e = std::fabs(ew.delta_energy(s.p, i, far) - ref.delta_energy(s.p, i, far));
      far2 += e * e;
      far_max = std::max(far_max, e);
    }
    small2 /= moves;
    far2 /= moves;
    total_err = std::fabs(ew.total_energy(s.p) - ref.total_energy(s.p)) / static_cast<double>(n);
  }
  state.counters["small_rms"] = std::sqrt(small2);
  state.counters["small_max"] = small_max;
  state.counters["far_rms"] = std::sqrt(far2);
  state.counters["far_max"] = far_max;
  state.counters["total_err_per_dipole"] = total_err;
  state.counters["kappa_ref"] = ref.parameters().kappa;
  state.counters["n_max_ref"] = ref.parameters().n_max;
}

}  // namespace

BENCHMARK(BM_Accuracy)->Args({1500, 0})->Args({1500, 1})->Args({125, 0})->Args({125, 1})->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Delta)->Args({1500, 5})->Args({125, 5})->Args({1500, 7})->Args({125, 7});
BENCHMARK(BM_DeltaAccept)->Arg(1500)->Arg(125);
BENCHMARK(BM_RealErfc)->Arg(1500)->Arg(125);
BENCHMARK(BM_Bare)->Arg(1500)->Arg(125);
BENCHMARK(BM_Rebuild)->Arg(1500)->Arg(125)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Total)->Arg(1500)->Arg(125)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();

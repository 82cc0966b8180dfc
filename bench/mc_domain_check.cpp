// Domain sweeps against the sequential sweep on a large isotropic system (issue 18), two checks
// that the unit tests are too small to make:
//
//   bench_mc_domain_check overlaps STATE.h5 CYCLES TRANSLATE ROTATE SWEEPS
//     NVT cycles from an H5MD state (SWEEPS: 0 sequential, 1 domains) with fixed move sizes,
//     every pair checked by brute force after every cycle; stops at the first overlap.
//   bench_mc_domain_check order N ETA CYCLES SWEEPS SEED T W L TRANSLATE ROTATE R_NEAR
//     N boards T×W×L placed on a lattice at packing fraction ETA (aligned: the first CYCLES/4
//     cycles are discarded), then CYCLES NVT cycles; every 20th adds to the averages the
//     largest eigenvalue U_L of the long axes' Q tensor and Σ P2(u_i·u_j)/N over the pairs whose
//     centres are closer than R_NEAR. Prints both means with block errors.
//   bench_mc_domain_check contacts STATE.h5 CYCLES TRANSLATE ROTATE SWEEPS SEED EPSILON
//     NVT cycles from an H5MD state; every 10th cycle, whether shrinking the box and the centres
//     by the relative volume EPSILON would make any pair overlap (what an NPT compression tests).
//     That probability depends only on the distribution of close contacts, so two sweeps that
//     sample the same ensemble give the same value within errors. Prints its mean with block errors.
//   bench_mc_domain_check npt STATE.h5 CYCLES TRANSLATE ROTATE LOG_VOLUME SWEEPS SEED BETA_P
//     NPT cycles (isotropic ln V moves of at most LOG_VOLUME) from an H5MD state; the first tenth
//     is discarded. Prints the volume moves' acceptance, and η and U_L (every 10th cycle) with
//     block errors: in equilibrium all three are properties of the ensemble, not of the sweep.
//     Also η's mean over each half of the sampled cycles, which differ while the volume relaxes.
//
// Not a timed benchmark: it prints results, not rates. docs/performance.md quotes its output.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <string>
#include <vector>

#include "anisodyn/core/statistics.hpp"
#include "anisodyn/geometry/overlap.hpp"
#include "anisodyn/interactions/hard_overlap.hpp"
#include "anisodyn/io/h5md.hpp"
#include "anisodyn/mc/mc_engine.hpp"
#include "anisodyn/system/order.hpp"
#include "lattice_states.hpp"

using namespace anisodyn;

namespace {

/// Overlapping pairs of a one-species configuration, every pair tested.
long overlapping_pairs(const State& s) {
  const Particles& p = s.particles;
  const Shape& shape = s.species[0].shape;
  const double rc = 2.0 * shape.circumradius();
  std::vector<Mat3> rot(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) rot[i] = p.orientation(i).toRotationMatrix();
  long n = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const Vec3 t = s.box.min_image(p.position(j) - p.position(i));
      if (t.squaredNorm() < rc * rc && overlap(shape, rot[i], shape, rot[j], t)) ++n;
    }
  return n;
}

/// Σ P2(u_i · u_j) / N over the long axes of the pairs closer than r_near.
double near_pair_order(const State& s, double r_near) {
  const Particles& p = s.particles;
  std::vector<Vec3> u(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) u[i] = p.orientation(i) * Vec3::UnitZ();
  double sum = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      if (s.box.min_image(p.position(j) - p.position(i)).squaredNorm() >= r_near * r_near) continue;
      const double c = u[i].dot(u[j]);
      sum += 1.5 * c * c - 0.5;
    }
  return sum / static_cast<double>(p.size());
}

const char* sweep_name(bool domains) { return domains ? "domains" : "sequential"; }

/// The sweep and the fixed move sizes given on the command line.
void set_sweep_and_moves(McEngine& mc, bool domains, const char* translate, const char* rotate) {
  mc.set_domain_sweeps(domains);
  mc.move_sizes().translate[0] = std::atof(translate);
  mc.move_sizes().rotate[0] = std::atof(rotate);
}

/// `discard` cycles, then `cycles` more, calling sample() after every `every`-th of those.
template <class Sample>
void sample_every(McEngine& mc, long discard, long cycles, long every, Sample&& sample) {
  for (long c = 0; c < discard; ++c) mc.cycle();
  for (long c = 0; c < cycles; ++c) {
    mc.cycle();
    if (c % every == 0) sample();
  }
}

int check_overlaps(char** argv) {
  State s = io::H5mdReader(argv[2]).read_frame(-1);
  const long cycles = std::atol(argv[3]);
  const bool domains = std::atoi(argv[6]) != 0;
  McEngine mc(s, RngState{5, 0, 0, 4});
  set_sweep_and_moves(mc, domains, argv[4], argv[5]);
  if (const long n = overlapping_pairs(s)) {
    std::printf("the start overlaps (%ld pairs)\n", n);
    return 1;
  }
  for (long c = 0; c < cycles; ++c) {
    mc.cycle();
    if (const long n = overlapping_pairs(s)) {
      std::printf("%s: %ld overlapping pairs after cycle %ld\n", sweep_name(domains), n, c);
      return 1;
    }
  }
  std::printf("%s: no overlap after any of %ld cycles\n", sweep_name(domains), cycles);
  return 0;
}

int compare_order(char** argv) {
  const auto n = static_cast<std::size_t>(std::atol(argv[2]));
  const double eta = std::atof(argv[3]);
  const long cycles = std::atol(argv[4]);
  const bool domains = std::atoi(argv[5]) != 0;
  const std::uint64_t seed = std::strtoull(argv[6], nullptr, 10);
  const Species board{"board", Shape::cuboid(std::atof(argv[7]), std::atof(argv[8]), std::atof(argv[9])), 1.0, {}, {}};
  const double r_near = std::atof(argv[12]);
  Rng rng(seed, 0);
  State s = testing_support::lattice_of(board, n, eta, rng);
  McEngine mc(s, RngState{seed, 0, 0, 4});
  set_sweep_and_moves(mc, domains, argv[10], argv[11]);
  std::vector<double> order, near;
  sample_every(mc, cycles / 4, cycles, 20, [&] {
    order.push_back(body_axis_order(s, 0)[2].order);
    near.push_back(near_pair_order(s, r_near));
  });
  const MeanError u = block_average(order), p2 = block_average(near);
  std::printf("%s seed %llu: U_L %.5f ± %.5f, near-pair P2/N %.5f ± %.5f, overlapping pairs at the end %ld\n", sweep_name(domains),
              static_cast<unsigned long long>(seed), u.mean, u.error, p2.mean, p2.error, overlapping_pairs(s));
  return 0;
}

/// Whether the configuration, shrunk by the relative volume eps (box and centres), overlaps.
bool overlaps_when_shrunk(const State& s, double eps) {
  State shrunk = s;
  const double f = std::cbrt(1.0 - eps);
  Particles& p = shrunk.particles;
  for (std::size_t i = 0; i < p.size(); ++i) p.set_position(i, p.position(i) * f);
  shrunk.box = Box(s.box.edges() * f);
  return HardOverlap(shrunk).any_overlap();
}

int compare_contacts(char** argv) {
  State s = io::H5mdReader(argv[2]).read_frame(-1);
  const long cycles = std::atol(argv[3]);
  const bool domains = std::atoi(argv[6]) != 0;
  const std::uint64_t seed = std::strtoull(argv[7], nullptr, 10);
  const double eps = std::atof(argv[8]);
  McEngine mc(s, RngState{seed, 0, 0, 4});
  set_sweep_and_moves(mc, domains, argv[4], argv[5]);
  std::vector<double> blocked, order;
  sample_every(mc, cycles / 10, cycles, 10, [&] {
    blocked.push_back(overlaps_when_shrunk(s, eps) ? 1.0 : 0.0);
    order.push_back(body_axis_order(s, 0)[2].order);
  });
  const MeanError b = block_average(blocked), u = block_average(order);
  std::printf("%s seed %llu: P(overlap after shrinking by %g) %.4f ± %.4f, U_L %.5f ± %.5f\n", sweep_name(domains),
              static_cast<unsigned long long>(seed), eps, b.mean, b.error, u.mean, u.error);
  return 0;
}

int compare_npt(char** argv) {
  State s = io::H5mdReader(argv[2]).read_frame(-1);
  const long cycles = std::atol(argv[3]);
  const bool domains = std::atoi(argv[7]) != 0;
  const std::uint64_t seed = std::strtoull(argv[8], nullptr, 10);
  McEngine mc(s, RngState{seed, 0, 0, 4});
  set_sweep_and_moves(mc, domains, argv[4], argv[5]);
  mc.set_pressure(std::atof(argv[9]));
  mc.move_sizes().log_volume = std::atof(argv[6]);
  for (long c = 0; c < cycles / 10; ++c) mc.cycle();
  const MoveCounters start = mc.counters();
  std::vector<double> eta, order;
  sample_every(mc, 0, cycles, 10, [&] {
    eta.push_back(s.packing_fraction());
    order.push_back(body_axis_order(s, 0)[2].order);
  });
  const MoveCounters w = mc.counters().since(start);
  const MeanError e = block_average(eta), u = block_average(order);
  // The halves' means show whether η still drifts (a run that relaxes compares routes, not ensembles).
  const auto half = eta.begin() + static_cast<std::ptrdiff_t>(eta.size() / 2);
  const double first = std::accumulate(eta.begin(), half, 0.0) / static_cast<double>(half - eta.begin());
  const double second = std::accumulate(half, eta.end(), 0.0) / static_cast<double>(eta.end() - half);
  std::printf("%s seed %llu: volume acceptance %.4f (%lld moves), eta %.5f ± %.5f, U_L %.5f ± %.5f, eta halves %.5f %.5f\n",
              sweep_name(domains), static_cast<unsigned long long>(seed), MoveCounters::ratio(w.volume_accepted, w.volume_tried),
              static_cast<long long>(w.volume_tried), e.mean, e.error, u.mean, u.error, first, second);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "overlaps" && argc == 7) return check_overlaps(argv);
  if (mode == "order" && argc == 13) return compare_order(argv);
  if (mode == "contacts" && argc == 9) return compare_contacts(argv);
  if (mode == "npt" && argc == 10) return compare_npt(argv);
  std::fprintf(stderr,
               "usage: %s overlaps STATE.h5 CYCLES TRANSLATE ROTATE SWEEPS\n"
               "       %s order N ETA CYCLES SWEEPS SEED T W L TRANSLATE ROTATE R_NEAR\n"
               "       %s contacts STATE.h5 CYCLES TRANSLATE ROTATE SWEEPS SEED EPSILON\n"
               "       %s npt STATE.h5 CYCLES TRANSLATE ROTATE LOG_VOLUME SWEEPS SEED BETA_P\n"
               "(SWEEPS: 0 sequential, 1 domains)\n",
               argv[0], argv[0], argv[0], argv[0]);
  return 2;
}

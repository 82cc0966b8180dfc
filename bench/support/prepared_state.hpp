#pragma once
// Benchmark states: a lattice at the target packing fraction (aligned along each shape's default
// axis, random azimuth) melted by NVT MC with tuned moves, prepared once and cached as H5MD in
// $ANISODYN_BENCH_CACHE (default ./bench-cache) so repeated runs time only the production loop.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "anisodyn/config/builder.hpp"
#include "anisodyn/io/h5md.hpp"
#include "anisodyn/mc/protocol.hpp"

namespace anisodyn::bench {

inline State lattice_at(const Species& sp, std::size_t n, double eta) {
  State s;
  s.species.push_back(sp);
  s.box = Box(box_edges_for_packing_fraction(s.species, {n}, eta, Vec3::Ones()));
  PlacementRequest req;
  req.counts = {n};
  OrientationRule rule;
  rule.body_axis = default_alignment_axis(sp.shape);
  rule.random_azimuth = true;
  req.rules = {rule};
  Rng rng(1, 1);
  place_on_lattice(s, req, rng);
  return s;
}

/// The cache folder ($ANISODYN_BENCH_CACHE, default ./bench-cache), created if missing.
inline std::string cache_dir() {
  const char* env = std::getenv("ANISODYN_BENCH_CACHE");
  const std::string dir = env ? env : "bench-cache";
  std::filesystem::create_directories(dir);
  return dir;
}

/// The state cached as `name`, or make() written to the cache first.
template <class Make>
State cached_state(const std::string& name, Make&& make) {
  const std::string path = cache_dir() + "/" + name + ".h5";
  if (std::filesystem::exists(path)) return io::H5mdReader(path).read_frame(-1);
  State s = make();
  io::H5mdWriter w(path, {"anisodyn", "", "bench", nlohmann::json::object(), nlohmann::json::object(), s.species});
  w.append_frame(s);
  w.commit();
  return s;
}

/// Runs `phases` of MC on `s`, in place; logs each phase's summary under `name`. The run's
/// trajectory is not kept (the writer is dropped without commit, which removes it).
inline void run_phases(State& s, const std::string& name, std::vector<McPhase> phases, const OrientationalField& field = {}) {
  McProtocol proto;
  proto.phases = std::move(phases);
  proto.field = field;
  McRunner runner(s, proto, false);
  io::H5mdWriter discarded(cache_dir() + "/" + name + ".prep.h5", {"anisodyn", "", "bench", nlohmann::json::object(),
                                                                   nlohmann::json::object(), s.species});
  runner.run(discarded, 0, [] {});
  for (const auto& phase : runner.summary()["phases"])
    std::fprintf(stderr, "prepared %s: %s\n", name.c_str(), phase.dump().c_str());
}

inline McPhase nvt_phase(std::int64_t cycles) {
  McPhase phase;
  phase.type = McPhase::Type::Nvt;
  phase.cycles = cycles;
  phase.tune = true;
  return phase;
}

/// NVT MC with move tuning on `s`, in place.
inline void melt(State& s, const std::string& name, std::int64_t cycles) { run_phases(s, name, {nvt_phase(cycles)}); }

inline State cached_melted_lattice(const std::string& name, const Species& sp, std::size_t n, double eta, std::int64_t melt_cycles) {
  return cached_state(name, [&] {
    State s = lattice_at(sp, n, eta);
    melt(s, name, melt_cycles);
    return s;
  });
}

/// A lattice placed at the dilute packing fraction `eta_start`, quick-compressed to `eta` with the
/// body L axes held along z by an orientational field of strength 10, then melted without it: for
/// shapes whose lattice at the target density is jammed along one axis (wide boards stacked face
/// to face), where melting the dense lattice leaves it ordered, and whose compression without the
/// field arrests isotropic.
inline State cached_compressed_lattice(const std::string& name, const Species& sp, std::size_t n, double eta_start,
                                       double eta, std::int64_t melt_cycles) {
  return cached_state(name, [&] {
    State s = lattice_at(sp, n, eta_start);
    McPhase compress;
    compress.type = McPhase::Type::Compress;
    compress.method = "quick";
    compress.target_packing_fraction = eta;
    compress.tune = true;
    run_phases(s, name, {compress}, OrientationalField{10.0, 2, Vec3::UnitZ()});
    run_phases(s, name, {nvt_phase(melt_cycles)});
    return s;
  });
}

/// A melted lattice of one species (box set by its packing fraction alone, as in spec 60 §A3)
/// with `n_small` particles of `small` inserted at random and re-equilibrated by NVT MC.
inline State cached_mixture(const std::string& name, const std::string& host_name, const Species& host, std::size_t n_host,
                            double eta, std::int64_t melt_cycles, const Species& small, std::size_t n_small,
                            std::int64_t mix_cycles) {
  return cached_state(name, [&] {
    State s = cached_melted_lattice(host_name, host, n_host, eta, melt_cycles);
    s.species.push_back(small);
    PlacementRequest req;
    req.counts = {0, n_small};
    req.rules = {OrientationRule{}, OrientationRule{}};
    Rng rng(2, 2);
    insert_randomly(s, req, rng);
    melt(s, name, mix_cycles);
    return s;
  });
}

}  // namespace anisodyn::bench

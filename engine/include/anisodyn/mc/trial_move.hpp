#pragma once
// One Metropolis trial move of one hard particle (spec 10 §3): a body-frame translation or, for
// anisotropic particles with probability 1/2, a body-frame rotation, rejected on overlap (or, during
// quick compression's overlap removal, unless it lowers the particle's overlap count). Shared by
// the sequential sweep of McEngine and the domain sweeps of DomainSweep, which run it on a part of
// the configuration with the particle held inside a domain.
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "anisodyn/core/rng.hpp"
#include "anisodyn/interactions/hard_overlap.hpp"
#include "anisodyn/interactions/orientational_field.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn {

struct MoveSizes {
  std::vector<double> translate;  // per species: largest body-frame displacement per axis
  std::vector<double> rotate;     // per species: largest body-frame rotation angle per axis [rad]
  double log_volume = 0.01;       // largest change of ln V (or ln L_k) per volume move
};

struct MoveCounters {
  std::vector<std::int64_t> translate_tried, translate_accepted, rotate_tried, rotate_accepted;
  std::int64_t volume_tried = 0, volume_accepted = 0;

  void reset(std::size_t nspecies);
  /// Counts accumulated since `earlier` (a copy taken before).
  MoveCounters since(const MoveCounters& earlier) const;
  /// Adds sign × the particle-move counts of `other` (same species count).
  void add_particle_moves(const MoveCounters& other, std::int64_t sign = 1);
  static double ratio(std::int64_t accepted, std::int64_t tried) {
    return tried > 0 ? static_cast<double>(accepted) / static_cast<double>(tried) : 0.0;
  }
};

/// The periodic slab [start, start + width) along a box axis. A body is inside when its lab
/// extent along the axis lies strictly within the slab: two bodies inside disjoint slabs cannot
/// overlap, whatever else they do.
struct Slab {
  int axis = 0;
  double start = 0.0;
  double width = 0.0;

  /// Whether the interval [c − h, c + h] (c a coordinate in a box of edge L, h < L/2) is inside.
  bool holds(double c, double h, double L) const {
    const double u = offset(c, L);
    return u - h > 0.0 && u + h < width;
  }
  /// Whether that interval meets the slab (or one of its periodic images).
  bool reaches(double c, double h, double L) const {
    const double u = offset(c, L);
    return (u - h <= width) | (u + h >= L);  // both sides evaluated, without a branch
  }

 private:
  /// c − start, wrapped into [0, L).
  double offset(double c, double L) const {
    double u = c - start;
    u -= L * std::floor(u / L);
    return u;
  }
};

/// A domain of a domain sweep: the intersection of slabs along the axes that are cut (an axis not
/// cut spans the periodic box). Bodies inside two disjoint domains are apart along some cut axis,
/// so they cannot overlap.
struct Domain {
  std::array<Slab, 3> along{};  // along[k] counts only where cut[k]
  std::array<bool, 3> cut{};

  /// Whether the lab box [c − h, c + h] lies inside along every cut axis.
  bool holds(const Vec3& c, const Vec3& h, const Vec3& L) const {
    bool inside = true;
    for (int k = 0; k < 3; ++k) inside = inside && (!cut[k] || along[k].holds(c[k], h[k], L[k]));
    return inside;
  }
  /// Whether the lab box meets the domain (or one of its periodic images).
  bool reaches(const Vec3& c, const Vec3& h, const Vec3& L) const {
    bool meets = true;
    for (int k = 0; k < 3; ++k) meets &= !cut[k] || along[k].reaches(c[k], h[k], L[k]);
    return meets;
  }
};

/// Everything one trial touches. `domain`, when set, rejects moves that take the body out of it.
struct TrialMove {
  State& state;
  HardOverlap& overlap;
  Rng& rng;
  MoveCounters& counters;
  const MoveSizes& moves;
  const OrientationalField& field;
  bool removing_overlaps = false;
  const Domain* domain = nullptr;

  void attempt(std::int32_t i) const;

 private:
  /// Whether the hard cores forbid moving particle i from (r_old, rot_old) to (r_new, rot_new).
  bool blocked(std::int32_t i, const Vec3& r_new, const Mat3& rot_new, const Vec3& r_old, const Mat3& rot_old) const;
  bool leaves_domain(int species, const Vec3& r, const Mat3& rot) const;
};

}  // namespace anisodyn

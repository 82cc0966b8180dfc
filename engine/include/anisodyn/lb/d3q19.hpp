#pragma once
// The D3Q19 lattice of spec 40 §2.1–2.2 in lattice units (a = Δt_LB = 1, c_s² = 1/3): the
// nineteen velocities with their weights, and the orthogonal mode basis of Dünweg, Schiller and
// Ladd (PRE 76, 036704, 2007), m_k = Σ_i e_ki n_i, with Σ_i w_i e_ki e_li = b_k δ_kl, so that
// n_i = w_i Σ_k e_ki m_k / b_k.
//
// Velocities come in opposite pairs: i and i + 1 for odd i (0 is rest). Everything is constexpr
// integers, so that the collision (lb/lb_fluid.cpp) adds only the non-zero terms of each mode.
#include <array>

namespace anisodyn::lb {

inline constexpr int kQ = 19;
inline constexpr double kCs2 = 1.0 / 3.0;

inline constexpr int kC[kQ][3] = {
    {0, 0, 0},                                                      //
    {1, 0, 0},  {-1, 0, 0}, {0, 1, 0},   {0, -1, 0}, {0, 0, 1},   {0, 0, -1},  // type (±1, 0, 0)
    {1, 1, 0},  {-1, -1, 0}, {1, -1, 0}, {-1, 1, 0},                            // type (±1, ±1, 0)
    {1, 0, 1},  {-1, 0, -1}, {1, 0, -1}, {-1, 0, 1},                            //
    {0, 1, 1},  {0, -1, -1}, {0, 1, -1}, {0, -1, 1}};

inline constexpr double kW[kQ] = {1.0 / 3,  1.0 / 18, 1.0 / 18, 1.0 / 18, 1.0 / 18, 1.0 / 18, 1.0 / 18,
                                  1.0 / 36, 1.0 / 36, 1.0 / 36, 1.0 / 36, 1.0 / 36, 1.0 / 36,
                                  1.0 / 36, 1.0 / 36, 1.0 / 36, 1.0 / 36, 1.0 / 36, 1.0 / 36};

/// The velocity opposite to i.
constexpr int opposite(int i) { return i == 0 ? 0 : (i % 2 == 1 ? i + 1 : i - 1); }

namespace detail {

constexpr int basis(int k, int i) {
  const int cx = kC[i][0], cy = kC[i][1], cz = kC[i][2];
  const int c2 = cx * cx + cy * cy + cz * cz;
  switch (k) {
    case 0: return 1;
    case 1: return cx;
    case 2: return cy;
    case 3: return cz;
    case 4: return c2 - 1;                                      // bulk
    case 5: return 3 * cx * cx - c2;                            // shear
    case 6: return cy * cy - cz * cz;
    case 7: return cx * cy;
    case 8: return cy * cz;
    case 9: return cz * cx;
    case 10: return (3 * c2 - 5) * cx;                          // ghosts
    case 11: return (3 * c2 - 5) * cy;
    case 12: return (3 * c2 - 5) * cz;
    case 13: return (cy * cy - cz * cz) * cx;
    case 14: return (cz * cz - cx * cx) * cy;
    case 15: return (cx * cx - cy * cy) * cz;
    case 16: return 3 * c2 * c2 - 6 * c2 + 1;
    case 17: return (2 * c2 - 3) * (3 * cx * cx - c2);
    default: return (2 * c2 - 3) * (cy * cy - cz * cz);
  }
}

constexpr std::array<std::array<int, kQ>, kQ> basis_table() {
  std::array<std::array<int, kQ>, kQ> e{};
  for (int k = 0; k < kQ; ++k)
    for (int i = 0; i < kQ; ++i) e[k][i] = basis(k, i);
  return e;
}

}  // namespace detail

/// e_ki: mode k's weight of population i.
inline constexpr std::array<std::array<int, kQ>, kQ> kE = detail::basis_table();

/// b_k = Σ_i w_i e_ki² (spec 40 §2.2's table).
inline constexpr double kB[kQ] = {1.0,       1.0 / 3, 1.0 / 3, 1.0 / 3, 2.0 / 3, 4.0 / 3, 4.0 / 9, 1.0 / 9, 1.0 / 9, 1.0 / 9,
                                  2.0 / 3,   2.0 / 3, 2.0 / 3, 2.0 / 9, 2.0 / 9, 2.0 / 9, 2.0,     4.0 / 3, 4.0 / 9};

/// Modes 0–3 (mass, momentum) are conserved; 4 is bulk, 5–9 shear, 10–18 ghosts.
inline constexpr int kFirstStressMode = 4, kFirstShearMode = 5, kFirstGhostMode = 10;

}  // namespace anisodyn::lb

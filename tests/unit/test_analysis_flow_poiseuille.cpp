// The periodic Poiseuille fit of anisodyn-flow (flow_profiles.hpp, compute_flow): slab sums made
// here from the closed-form profile v_x = ±A u (h − u) + B with a known η give η back to rounding,
// with and without noise on the slab velocities (then within the jackknife's error, which must be
// of the size of the noise put in), and the slip fit is not touched by it.
#include <gtest/gtest.h>

#include <cmath>

#include "anisodyn/analysis/flow_profiles.hpp"
#include "anisodyn/core/rng.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

constexpr double kForce = 0.05, kEta = 2.5, kDensity = 3.0, kOffset = 0.01;
constexpr double kBin = 0.25, kHeight = 16.0, kArea = 36.0;

/// `rows` rows of slab sums for the closed-form profile, each slab velocity with normal noise of
/// standard deviation `noise` per row.
ProfileSums sample(double rows, double noise, Rng& rng) {
  const auto bins = static_cast<std::size_t>(kHeight / kBin);
  const double h = kHeight / 2, amplitude = kDensity * kForce / (2 * kEta);
  const double count = kDensity * kArea * kBin;  // particles per slab per row
  ProfileSums s;
  s.rows = rows;
  for (std::size_t k = 0; k < bins; ++k) {
    const double z = (static_cast<double>(k) + 0.5) * kBin, u = z < h ? z : z - h;
    const double v = (z < h ? 1.0 : -1.0) * amplitude * u * (h - u) + kOffset;
    double vx_sum = 0.0;
    for (int row = 0; row < static_cast<int>(rows); ++row) vx_sum += count * (v + noise * rng.normal());
    s.z_count.push_back(count * rows);
    s.z_vx.push_back(vx_sum);
  }
  return s;
}

FlowGeometry geometry() {
  FlowGeometry g;
  g.z_bin = kBin;
  g.area = kArea;
  return g;
}

}  // namespace

TEST(FlowPoiseuille, TheViscosityOfTheClosedFormProfile) {
  Rng rng(1, 0);
  const std::vector<ProfileSums> samples = {sample(10, 0.0, rng), sample(12, 0.0, rng), sample(9, 0.0, rng)};
  const FlowResult r = compute_flow(geometry(), samples, std::nullopt, PoiseuilleSettings{kForce});
  ASSERT_TRUE(r.viscosity && r.poiseuille_amplitude);
  EXPECT_NEAR(r.viscosity->value, kEta, 1e-12 * kEta);
  EXPECT_NEAR(r.poiseuille_amplitude->value, kDensity * kForce / (2 * kEta), 1e-14);
  EXPECT_LT(r.viscosity->error, 1e-10);
  EXPECT_FALSE(r.slip_length) << "no slip fit was asked for";
}

TEST(FlowPoiseuille, NoisyProfilesGiveTheViscosityWithinItsError) {
  // 20 blocks of 5 rows, each slab velocity with noise 0.02 per row: the amplitude's error is that
  // of a line through 64 points, about 0.02 / √(5 · 20 · 64 · Σ(x − x̄)²/64) — checked only as
  // being small against the amplitude (0.03) and the estimate within 3.5 of its errors.
  Rng rng(2, 0);
  std::vector<ProfileSums> samples;
  for (int b = 0; b < 20; ++b) samples.push_back(sample(5, 0.02, rng));
  const FlowResult r = compute_flow(geometry(), samples, std::nullopt, PoiseuilleSettings{kForce});
  ASSERT_TRUE(r.viscosity);
  EXPECT_GT(r.viscosity->error, 0.0);
  EXPECT_LT(r.viscosity->error, 0.02 * kEta);
  EXPECT_LT(std::abs(r.viscosity->value - kEta), 3.5 * r.viscosity->error) << r.viscosity->value << " ± " << r.viscosity->error;
}

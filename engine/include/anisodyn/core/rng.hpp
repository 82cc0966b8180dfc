#pragma once
// Counter-based random numbers (Random123 Philox4x64-10) keyed by (seed, stream). A generator's
// whole state is (seed, stream, counter, position in the current block), so it checkpoints as four
// integers and the same key always gives the same sequence, whatever the thread count.
#include <Random123/philox.h>

#include <array>
#include <cmath>
#include <cstdint>

namespace anisodyn {

struct RngState {
  std::uint64_t seed = 0, stream = 0, counter = 0;
  std::uint32_t used = 4;  // draws consumed from the block at counter-1 (4 = block exhausted)
};

class Rng {
 public:
  Rng() = default;
  Rng(std::uint64_t seed, std::uint64_t stream) { state_.seed = seed; state_.stream = stream; }
  explicit Rng(const RngState& s) : state_(s) {
    if (state_.used < 4) refill(state_.counter - 1);
  }

  const RngState& state() const { return state_; }

  std::uint64_t bits() {
    if (state_.used >= 4) {
      refill(state_.counter++);
      state_.used = 0;
    }
    return block_[state_.used++];
  }
  /// Uniform double in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(bits() >> 11) * 0x1.0p-53; }
  /// Uniform double in (0, 1]: safe for logarithms.
  double uniform_open0() { return (static_cast<double>(bits() >> 11) + 1.0) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Uniform integer in [0, n), by Lemire's multiply-shift (bias < n/2^64, irrelevant here).
  std::uint64_t index(std::uint64_t n) {
    __extension__ using u128 = unsigned __int128;
    return static_cast<std::uint64_t>((static_cast<u128>(bits()) * n) >> 64);
  }
  /// Standard normal draw (Box–Muller, one value per pair of uniforms so that RngState is the
  /// complete state of the generator).
  double normal() {
    const double r = std::sqrt(-2.0 * std::log(uniform_open0()));
    return r * std::cos(2.0 * M_PI * uniform());
  }

 private:
  void refill(std::uint64_t counter) {
    using G = r123::Philox4x64;
    G gen;
    G::ctr_type ctr = {{counter, 0, 0, 0}};
    G::key_type key = {{state_.seed, state_.stream}};
    const G::ctr_type out = gen(ctr, key);
    for (int k = 0; k < 4; ++k) block_[k] = out[k];
  }

  RngState state_;
  std::array<std::uint64_t, 4> block_{};
};

}  // namespace anisodyn

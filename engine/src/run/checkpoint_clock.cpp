#include "anisodyn/run/checkpoint_clock.hpp"

#include "anisodyn/core/error.hpp"
#include "anisodyn/core/signals.hpp"

namespace anisodyn::run {

void CheckpointClock::tick(std::int64_t done, const std::string& where) {
  if (interrupt_requested()) {
    write();
    throw Interrupted("checkpoint written at " + where + "; run again to resume");
  }
  if (every_ > 0 && done % every_ == 0) write();
}

}  // namespace anisodyn::run

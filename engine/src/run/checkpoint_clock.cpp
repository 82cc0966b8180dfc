#include "anisodyn/run/checkpoint_clock.hpp"

#include "anisodyn/core/error.hpp"
#include "anisodyn/core/signals.hpp"

namespace anisodyn::run {

void CheckpointClock::tick_if(bool due, const std::string& where) {
  if (interrupt_requested()) {
    write();
    throw Interrupted("checkpoint written at " + where + "; run again to resume");
  }
  if (due) write();
}

}  // namespace anisodyn::run

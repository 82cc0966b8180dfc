#include "anisodyn/core/signals.hpp"

#include <csignal>

namespace anisodyn {
namespace {
volatile std::sig_atomic_t g_interrupted = 0;
extern "C" void on_interrupt(int) { g_interrupted = 1; }
}  // namespace

void install_interrupt_handlers() {
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
}

bool interrupt_requested() { return g_interrupted != 0; }
void clear_interrupt_request() { g_interrupted = 0; }
}  // namespace anisodyn

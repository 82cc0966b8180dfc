#pragma once
// SIGINT/SIGTERM set a flag that long runs poll at cycle boundaries: they then write a checkpoint
// and exit with code 130 instead of dying mid-write.
namespace anisodyn {
void install_interrupt_handlers();
bool interrupt_requested();
/// Forgets a request once it has been handled without leaving the process (tests that interrupt
/// a run and resume it in the same process).
void clear_interrupt_request();
}  // namespace anisodyn

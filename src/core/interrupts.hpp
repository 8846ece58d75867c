// Cancellation for long C++ loops. Core code cannot call CHECK_FOR_INTERRUPTS (it longjmps over
// C++ frames), so the boundary installs a probe that only reads PostgreSQL's pending flag; loops
// call poll_interrupts(), which throws ErrorKind::canceled, and the boundary lets PostgreSQL raise
// the real cancel or timeout error once every C++ object is gone.
#pragma once
#include "core/no_postgres.hpp"

#include <cstddef>

namespace streetgen::core {

using InterruptProbe = bool (*)() noexcept;

// Sets the probe (nullptr: never interrupted). Returns the previous one.
InterruptProbe set_interrupt_probe(InterruptProbe probe) noexcept;

// Throws Error(canceled) if the probe reports a pending interrupt.
void poll_interrupts();

// Polls every `period` calls of tick(); for tight loops where one probe per iteration would show.
class InterruptPoller {
 public:
  explicit InterruptPoller(std::size_t period = 4096) : period_(period) {}
  void tick() {
    if (++count_ % period_ == 0) poll_interrupts();
  }

 private:
  std::size_t period_;
  std::size_t count_ = 0;
};

}  // namespace streetgen::core

#include "core/interrupts.hpp"

#include <atomic>

#include "core/error.hpp"

namespace streetgen::core {
namespace {
std::atomic<InterruptProbe> g_probe{nullptr};
}

InterruptProbe set_interrupt_probe(InterruptProbe probe) noexcept { return g_probe.exchange(probe); }

void poll_interrupts() {
  InterruptProbe probe = g_probe.load(std::memory_order_relaxed);
  if (probe != nullptr && probe()) {
    throw Error(ErrorKind::canceled, "streetgen computation interrupted");
  }
}

}  // namespace streetgen::core

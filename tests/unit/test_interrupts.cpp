#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/interrupts.hpp"

using namespace streetgen;

namespace {
bool g_pending = false;
bool probe() noexcept { return g_pending; }

struct ProbeGuard {
  core::InterruptProbe previous = core::set_interrupt_probe(&probe);
  ~ProbeGuard() {
    core::set_interrupt_probe(previous);
    g_pending = false;
  }
};
}  // namespace

TEST(Interrupts, PollThrowsCanceledOnlyWhenPending) {
  ProbeGuard guard;
  g_pending = false;
  EXPECT_NO_THROW(core::poll_interrupts());
  g_pending = true;
  try {
    core::poll_interrupts();
    FAIL() << "no exception";
  } catch (const core::Error& e) {
    EXPECT_EQ(e.kind(), core::ErrorKind::canceled);
  }
}

TEST(Interrupts, PollerProbesEveryPeriodTicks) {
  ProbeGuard guard;
  g_pending = true;
  core::InterruptPoller poller(10);
  for (int i = 1; i < 10; ++i) EXPECT_NO_THROW(poller.tick()) << i;
  EXPECT_THROW(poller.tick(), core::Error);
}

TEST(Interrupts, NoProbeNeverInterrupts) {
  core::InterruptProbe previous = core::set_interrupt_probe(nullptr);
  EXPECT_NO_THROW(core::poll_interrupts());
  core::set_interrupt_probe(previous);
}

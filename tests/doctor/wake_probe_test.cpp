// The doctor's wake-up probe on this machine: it starts a thread that sleeps the pulse thread's
// deadline sleep (rt/deadline_sleep) and measures how late each wake-up is. Label threading: it
// starts a thread (qemu-user cannot, so the arm64 stage leaves it out with the other threading
// tests), and the ThreadSanitizer stage runs it.
#include <gtest/gtest.h>

#include "doctor/wake_probe.hpp"

namespace stepmod::doctor {
namespace {

TEST(DoctorWakeProbe, MeasuresWakeUpsThroughThePulseThreadsSleep) {
  WakeProbeOptions o;
  o.thread.priority = 0;  // SCHED_OTHER: runs unprivileged
  o.thread.lock_memory = false;
  o.duration = 200 * kNsPerMs;  // long enough that a stalled virtual CPU still leaves many wake-ups
  o.interval = kNsPerMs;
  const WakeProbeResult r = run_wake_probe(o);
  EXPECT_TRUE(r.status.started);
  EXPECT_GT(r.late.count(), 10u);
  EXPECT_LE(r.late.count(), 200u);
}

}  // namespace
}  // namespace stepmod::doctor

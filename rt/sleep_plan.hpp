#pragma once
// When the pulse thread, with no edge due within its spin, wakes next (why: the doorbell in
// rt/pulse_thread.hpp). It polls every max_sleep_ns while a producer said work may come (a
// ring() within awake_ns: DoorbellWindow) or while a motion is starved (its ring ran dry before
// its last edge) and the planner's next edge for it may be due (AxisControl::refill_at, less
// the spin: it is an edge time); otherwise it sleeps up to quiet_sleep_ns, to its next edge or
// to the time the planner named, whichever comes first. A wake for an edge is `spin` before it.
//
// Pulse-thread code: pure arithmetic, no allocation, no system call.
#include <algorithm>
#include <cstdint>

#include "core/clock.hpp"
#include "rt/pulse_engine.hpp"

namespace stepmod::rt {

// The doorbell's counter as the thread last saw it, and until when its last ring keeps the
// short poll on.
class DoorbellWindow {
 public:
  DoorbellWindow(std::uint32_t bell, Nanos awake_ns) noexcept : bell_(bell), awake_ns_(awake_ns) {}

  // The counter read now: a new value is a ring() since the last look.
  void see(std::uint32_t bell, Nanos now) noexcept {
    if (bell == bell_) return;
    bell_ = bell;
    awake_until_ = now + awake_ns_;
  }
  bool awake(Nanos now) const noexcept { return now < awake_until_; }
  // The value to sleep on: a ring() changes it and ends the sleep.
  std::uint32_t bell() const noexcept { return bell_; }

 private:
  std::uint32_t bell_;
  Nanos awake_ns_;
  Nanos awake_until_ = 0;
};

struct SleepLimits {
  Nanos max_sleep_ns;    // the poll
  Nanos quiet_sleep_ns;  // the sleep with nothing expected (>= max_sleep_ns)
};

// What the engine says about its starved axes (PulseEngine::starved(), dry_until()).
struct DryRing {
  bool starved;
  Nanos until;  // read only when starved
};

struct SleepPlan {
  Nanos wake;     // absolute CLOCK_MONOTONIC
  bool for_edge;  // the wake is `spin` before the next edge: its lateness is worth measuring
  bool starved;   // a short poll because of a starved ring
};

// `next_edge`: the engine's next due time (kNever: none), later than now + spin.
inline SleepPlan plan_sleep(Nanos now, Nanos next_edge, Nanos spin, bool awake, DryRing dry,
                            const SleepLimits& limits) noexcept {
  const Nanos dry_wake = dry.starved ? dry.until - spin : kNever;
  const bool starved = dry.starved && dry_wake <= now;
  const bool poll = awake || starved;
  SleepPlan plan{now + (poll ? limits.max_sleep_ns : limits.quiet_sleep_ns), false, starved};
  plan.for_edge = next_edge != kNever && next_edge - spin <= plan.wake;
  if (plan.for_edge) plan.wake = next_edge - spin;
  if (!poll && dry_wake < plan.wake) plan.wake = dry_wake;  // not polling: dry_wake > now
  return plan;
}

}  // namespace stepmod::rt

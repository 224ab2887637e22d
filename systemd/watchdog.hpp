#pragma once
// systemd's service watchdog (WatchdogSec= in the unit): stepmodd pets it only while both its
// control thread (the caller, once per scan) and its pulse thread (whose loop counter must have
// moved since the last pet) are alive. A hung pulse thread or a stuck scan therefore stops the
// petting, and systemd restarts the service.
#include <cstdint>

#include "core/clock.hpp"

namespace stepmod::systemd {

// The decision alone, without systemd: unit-tested.
class WatchdogPolicy {
 public:
  // interval_ns: time between pets (half of WatchdogSec, as sd_watchdog_enabled(3) advises);
  // 0 = watchdog off (never pet).
  explicit WatchdogPolicy(Nanos interval_ns) : interval_(interval_ns) {}

  // Called once per scan. true: pet now. The pulse thread's loop counter must differ from the
  // one seen at the last pet: it loops at least every quiet_sleep_ns (100 ms) even when idle.
  bool due(Nanos now, std::uint64_t pulse_loops) noexcept;

  Nanos interval() const noexcept { return interval_; }

 private:
  Nanos interval_;
  Nanos last_pet_ = 0;
  std::uint64_t last_loops_ = 0;
  bool petted_ = false;
};

// The policy, fed from the environment systemd gives a service (WATCHDOG_USEC, WATCHDOG_PID);
// pets with sd_notify("WATCHDOG=1"). Without them (or without libsystemd) it never pets.
class Watchdog {
 public:
  Watchdog();
  bool enabled() const noexcept { return policy_.interval() > 0; }
  void scan(Nanos now, std::uint64_t pulse_loops);

 private:
  WatchdogPolicy policy_;
};

}  // namespace stepmod::systemd

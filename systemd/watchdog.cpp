#include "systemd/watchdog.hpp"

#ifdef STEPMOD_HAVE_LIBSYSTEMD
#include <systemd/sd-daemon.h>
#endif

namespace stepmod::systemd {

bool WatchdogPolicy::due(Nanos now, std::uint64_t pulse_loops) noexcept {
  if (interval_ <= 0) return false;
  if (petted_ && now - last_pet_ < interval_) return false;
  // The first pet needs no progress yet (the pulse thread has just started); every later one
  // needs the pulse thread to have looped since the previous pet.
  if (petted_ && pulse_loops == last_loops_) return false;
  petted_ = true;
  last_pet_ = now;
  last_loops_ = pulse_loops;
  return true;
}

namespace {
Nanos interval_from_environment() {
#ifdef STEPMOD_HAVE_LIBSYSTEMD
  std::uint64_t usec = 0;
  if (sd_watchdog_enabled(0, &usec) > 0 && usec > 0) {
    return static_cast<Nanos>(usec) * 1000 / 2;
  }
#endif
  return 0;
}
}  // namespace

Watchdog::Watchdog() : policy_(interval_from_environment()) {}

void Watchdog::scan(Nanos now, std::uint64_t pulse_loops) {
  if (!policy_.due(now, pulse_loops)) return;
#ifdef STEPMOD_HAVE_LIBSYSTEMD
  sd_notify(0, "WATCHDOG=1");
#endif
}

}  // namespace stepmod::systemd

#pragma once
// The charge-pump output (an extension, the AMCI modules have none; docs/safety.md "Charge
// pump"): a square wave on one line while the module is healthy and scanning, for a watchdog
// relay board (a retriggerable monostable) in the E-stop chain or the drives' enable. The relay
// holds while the line toggles and drops once it stops, at whichever level. The control thread
// toggles it every `half_period_scans` scans, so a control thread that stops scanning stops it
// too. It stops at the scan that sees a cause (held at its inactive level) and runs again once
// every cause is gone, as a drive enable is asserted again; a stop of the daemon is for good.
#include "core/clock.hpp"
#include "gpio/backend.hpp"

namespace stepmod::tools {

class ChargePump {
 public:
  struct Setup {
    unsigned axis = 0;  // the axis whose lines carry the pump: the module's first
    unsigned half_period_scans = 1;
    unsigned frequency_hz = 0;  // for the log
  };
  // What stops it; all false: it runs.
  struct Conditions {
    bool estop = false;          // an E-stop input is active
    bool fault = false;          // a late-edge fault or lost input events stand (health 0, 5)
    bool plc_lost = false;       // PLC heartbeat stale or output sequence stuck (health 1, 2)
    bool lease_expired = false;  // a commissioning lease expired without release (health 6)
    bool trace_lost = false;     // the --trace VCD lost records (health 4): motion unseen
  };

  // `clock`: read right after each write, so the trace shows the wire change itself (as
  // DriveEnable's). Null: the `now` given (unit tests).
  ChargePump(gpio::Backend& backend, const Setup& setup, Nanos (*clock)() = nullptr);

  // Control thread, after each scan: a toggle every half period while no condition holds, the
  // inactive level at once when one does. True when the line changed (level(), changed_at()).
  bool scan(const Conditions& c, Nanos now);
  // The daemon stops: inactive for good. True when the line changed.
  bool stop(Nanos now);

  bool running() const noexcept { return running_; }
  bool level() const noexcept { return level_; }  // logical: true = active
  Nanos changed_at() const noexcept { return changed_at_; }

 private:
  // Why the pump must not run, or nullptr.
  static const char* stop_reason(const Conditions& c) noexcept;
  bool halt(const char* why, Nanos now);
  bool write(bool level, Nanos now);

  gpio::Backend& backend_;
  Setup setup_;
  Nanos (*clock_)() = nullptr;
  bool running_ = false;
  bool stopped_for_good_ = false;
  bool level_ = false;
  unsigned scans_ = 0;  // scans into the present half period
  Nanos changed_at_ = 0;
};

}  // namespace stepmod::tools

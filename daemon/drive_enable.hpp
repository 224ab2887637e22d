#pragma once
// Drive-enable outputs (an extension: the AMCI modules have none): per axis, an optional `enable`
// line asserted while the axis is configured, released on the conditions its configuration
// lists (E-stop, faults, PLC loss, configuration mode; none by default: releasing a drive drops
// its holding torque, and a vertical axis falls), at daemon exit and before a configuration.
// After asserting, commands wait `enable_delay_us` for the drive to be ready: meanwhile the
// module is given the PLC's previous output words, so a command issued then is acted on (as a
// new edge) when the delay ends, and no step goes out to a drive that is not ready.
#include <cstdint>
#include <vector>

#include "core/clock.hpp"
#include "gpio/backend.hpp"

namespace stepmod::tools {

class DriveEnable {
 public:
  struct AxisSetup {
    bool wired = false;
    Nanos delay_ns = 0;
    std::uint8_t release = 0;  // tools::EnableRelease bits
  };
  struct Conditions {
    bool configured = false;
    bool configuration_mode = false;
    bool estop = false;
    bool fault = false;  // a late-edge fault or lost input events stopped the axis
    bool plc_lost = false;
  };

  // `clock`: read right after the enable line is written, so that the delay counts from the wire
  // change itself (a control thread preempted between its scan time and the write would
  // otherwise shorten the drive's wait). Null: the `now` given to update() (unit tests).
  DriveEnable(gpio::Backend& backend, std::vector<AxisSetup> axes, Nanos (*clock)() = nullptr);

  // Control thread, after each module scan: asserts or releases the axis' enable. True when the
  // line changed (changed_at() is then the time of the write).
  bool update(unsigned axis, const Conditions& c, Nanos now);
  // Whether a drive asserted less than its delay ago is not ready yet (commands wait).
  bool holding(Nanos now) const noexcept;
  bool asserted(unsigned axis) const noexcept { return state_[axis].asserted; }
  bool wired(unsigned axis) const noexcept { return axis < axes_.size() && axes_[axis].wired; }
  // When the axis' enable line last changed (the VCD's axis<N>.enable edge); 0 before that.
  Nanos changed_at(unsigned axis) const noexcept { return state_[axis].changed_at; }
  bool any_wired() const noexcept;

 private:
  struct State {
    bool asserted = false;
    Nanos ready_at = 0;
    Nanos changed_at = 0;
  };
  // Why the drive must be released now, or nullptr to assert it.
  const char* release_reason(const AxisSetup& s, const Conditions& c) const noexcept;

  gpio::Backend& backend_;
  std::vector<AxisSetup> axes_;
  std::vector<State> state_;
  Nanos (*clock_)() = nullptr;
};

}  // namespace stepmod::tools

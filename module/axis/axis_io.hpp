#pragma once
// What the module layer takes from the machine's I/O, without knowing how it is wired: the
// daemon adapts its GPIO backend to this (daemon/module_io.hpp), so that module/ depends on no
// GPIO code and a test can hand it any machine. Control thread, like every module call.
#include <cstdint>

#include "core/clock.hpp"
#include "core/lines.hpp"

namespace stepmod::module {

// An input edge: the line's electrical level after the change, stamped `t` with the
// CLOCK_MONOTONIC time of the edge itself (not the time it was read).
struct InputEvent {
  Nanos t = 0;
  std::uint8_t axis = 0;
  InputLine line = InputLine::kCapture;
  bool level = false;
};

class AxisIo {
 public:
  virtual ~AxisIo() = default;

  // Which inputs are wired, and their electrical level at start-up (later levels come as
  // InputEvents). An unwired line reads low.
  virtual bool has_input(unsigned axis, InputLine line) const noexcept = 0;
  virtual bool read(unsigned axis, InputLine line) = 0;

  // The pulse format a configuration sets (step/direction, or CW/CCW pulses: 3601 configuration
  // MSW bit 10). A real drive is set up to match it; a simulated one follows it.
  virtual void set_pulse_format(unsigned axis, bool step_dir) noexcept = 0;
};

}  // namespace stepmod::module

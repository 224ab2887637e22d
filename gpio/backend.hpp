#pragma once
// The one interface between stepmod and its GPIO lines. Two backends implement it:
//   SimBackend   - the built-in simulated machine (docs/interface.md sections 2 [axis.sim], 4)
//   GpiodBackend - a real chip through libgpiod (1.6 or >= 2, gpio/gpiod_backend.hpp), input
//                  events through io_uring
// Step and direction outputs are written by the pulse thread, the drive-enable outputs by the
// control thread; inputs are consumed by the control thread.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "core/clock.hpp"
#include "core/lines.hpp"
#include "gpio/line_options.hpp"

namespace stepmod::gpio {

// Config-file key of each line (docs/interface.md section 2), also the VCD wire suffix.
std::string_view input_key(InputLine l) noexcept;
std::string_view output_key(OutputLine l) noexcept;

// An input edge as the hardware saw it: electrical level after the change, stamped with the
// CLOCK_MONOTONIC time of the edge itself (kernel timestamp for gpiod, step time for sim).
struct InputEvent {
  Nanos t = 0;
  std::uint8_t axis = 0;
  InputLine line = InputLine::kCapture;
  bool level = false;
};

// How a drive interprets the two pulse outputs; the simulated drive follows the module's
// configuration (3601 config MSW bit 10) the way a real drive is set up to match it.
enum class PulseFormat : std::uint8_t { kStepDir, kCwCcw };

class Backend {
 public:
  virtual ~Backend() = default;

  virtual unsigned axes() const noexcept = 0;

  // Pulse thread. Drives one output line; `t` is the CLOCK_MONOTONIC time of the write (the sim
  // stamps the input edges it causes with it). Real-time safe: no allocation, no lock, no
  // logging, at most the one system call that writes the line.
  virtual void write(unsigned axis, OutputLine line, bool level, Nanos t) noexcept = 0;

  // Control thread. Whether a line is configured (wired) at all.
  virtual bool has_input(unsigned axis, InputLine line) const noexcept = 0;
  virtual bool has_output(unsigned axis, OutputLine line) const noexcept = 0;

  // Control thread. Present electrical level of an input; false for an unwired line.
  virtual bool read(unsigned axis, InputLine line) = 0;

  // Control thread. Blocks until at least one input event is available or `deadline` passes;
  // returns the number of events stored in `out` (0 on timeout). Events of one line arrive in
  // time order. An edge lost on the way (a line's kernel FIFO, or the sim's ring in its place,
  // overflowed) is never delivered: `lost_events()` counts the ones the backend can detect.
  virtual std::size_t wait_events(std::span<InputEvent> out, Nanos deadline) = 0;
  virtual std::uint64_t lost_events() const noexcept = 0;

  // Any thread, while the pulse thread is stopped: drive every output to its idle level (low).
  // The drive-enable outputs are released too, and the charge pump is inactive.
  virtual void idle_outputs() noexcept = 0;

  // Control thread: assert (true) or release the axis' drive-enable output, if it has one
  // (AxisLines::enable; `active_low` gives its polarity). No-op without one.
  virtual void set_enable(unsigned /*axis*/, bool /*asserted*/) noexcept {}
  // Control thread: drive the charge-pump output carried by the axis' lines
  // (AxisLines::charge_pump) to its active (true) or inactive level. No-op without one.
  virtual void set_charge_pump(unsigned /*axis*/, bool /*active*/) noexcept {}

  // Any thread: the electrical options of a configured line (`line`: an OutputLine or InputLine
  // value as `input` says). Levels everywhere else are logical; the VCD shows the wire, which is
  // inverted for an active-low line.
  virtual LineOptions line_options(unsigned /*axis*/, bool /*input*/,
                                   unsigned /*line*/) const noexcept {
    return {};
  }

  // Control thread: the module's configured pulse format (only the sim drive uses it).
  virtual void set_pulse_format(unsigned /*axis*/, PulseFormat /*format*/) noexcept {}
};

}  // namespace stepmod::gpio

#pragma once
// What the control thread asks of an emulated module. One implementation per module type
// (module_types/m3601/module_3601.hpp, module_types/m3602/module_3602.hpp, module_types/m3202/module_3202.hpp),
// made by its registry row (registry/module_registry.hpp): the module's dialect around the
// shared axis of module/axis/ (docs/ARCHITECTURE.md "The module layer").
#include <array>
#include <cstdint>
#include <memory>
#include <span>

#include "core/module_shape.hpp"
#include "module/axis/axis_io.hpp"
#include "module/axis/error_reason.hpp"

namespace stepmod::module {

class Personality {
 public:
  virtual ~Personality() = default;

  virtual const ModuleShape& shape() const noexcept = 0;

  // An input edge (electrical level, own timestamp), delivered in time order as soon as the
  // control thread sees it, between scans.
  virtual void on_input(const InputEvent& e) = 0;

  // One I/O scan: `plc_out` is a consistent snapshot of the PLC's output words; the personality
  // writes the whole input image into `plc_in`.
  virtual void scan(const ImageWords& plc_out, ImageWords& plc_in, Nanos now) = 0;

  // The PLC left Run mode (heartbeat timeout, docs/interface.md 3.2): every move stops and the
  // position becomes invalid, as the manuals say of a PLC switched to Program mode.
  virtual void plc_stopped(Nanos now) = 0;
  // The daemon stops every moving axis for a reason of its own, named by `why` (a stepmod item
  // of axis/error_items.hpp): a commissioning lease expired without release
  // (docs/interface.md 3.5), an input edge lost. As plc_stopped: immediate stop, position invalid.
  virtual void stop_every_axis(const axis::Item& why, Nanos now) = 0;

  // The last reason recorded for an error bit of axis/channel `axis` (0-based;
  // docs/error-reasons.md); the control thread publishes it with the input image.
  virtual axis::ErrorReason reason(unsigned axis) const = 0;

  // A message arrived through the image's mailbox (docs/interface.md 3: the 3202's 52-DINT blend
  // message); returns the message result (0 accepted). Modules without messages refuse it.
  virtual std::int32_t on_message(std::span<const std::int32_t> data, Nanos now) {
    (void)data;
    (void)now;
    return 1;
  }

  // Shutdown: immediate stop of every axis.
  virtual void shutdown() = 0;

  // Axis `axis` (0-based) as a drive-enable output needs it: configured, in configuration mode,
  // E-stop active (a 3202 channel or 3602 axis disabled by its configuration is not configured).
  struct DriveState {
    bool configured = false;
    bool configuration_mode = false;
    bool estop = false;
  };
  virtual DriveState drive_state(unsigned axis) const noexcept = 0;

  // The input lines of axis `axis` (0-based) as the module sees them, bit n = InputLine n
  // (capture, external, home, E-stop, CW, CCW limit): the electrical level now, whether the
  // configuration in force uses the input, and whether it is active (used, at its active level).
  // For a console's inputs panel (docs/interface.md 3.6).
  struct InputLines {
    std::uint16_t levels = 0;
    std::uint16_t used = 0;
    std::uint16_t active = 0;
  };
  virtual InputLines input_lines(unsigned axis) const noexcept = 0;
};

// The personality of each module type is made by its registry row (registry/module_registry.hpp).

}  // namespace stepmod::module

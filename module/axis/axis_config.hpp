#pragma once
// The decoded configuration of one axis/channel: what the configuration words mean, whatever
// module wrote them. A dialect (module/m3601/...) turns its configuration words into this value
// or into its manual's configuration error; the shared axis code reads only this.
#include <cstdint>

#include "core/clock.hpp"
#include "core/lines.hpp"

namespace stepmod::module::axis {

// The four homing options (3601 Ch.3 "Configuration Bits MSW", Ch.4 "Find Home"): which signal
// finds home and which signal is the proximity that slows down before it.
enum class HomingVariant : std::uint8_t {
  kSwitch = 0,               // (1) home limit switch only (H-A)
  kSwitchWithBackplane = 1,  // (2) home switch gated by the backplane proximity bit (H-B)
  kMarkerWithHome = 2,       // (3) marker pulse, the home input is the proximity (H-D)
  kMarkerWithBackplane = 3,  // (4) marker pulse, the backplane bit is the proximity (H-D)
};

// What a CW / CCW input does (3602: configurable; 3601/3202: always an end limit).
enum class LimitFunction : std::uint8_t { kUnused, kLimit, kEStop };

struct AxisConfig {
  // Discrete inputs: bit n = InputLine n (capture, external, home, E-stop, CW limit, CCW limit).
  std::uint16_t inputs_used = 0;
  std::uint16_t inputs_active_high = 0;  // 1 = active when the line is high (N.O. contact)
  bool quadrature_encoder = false;       // the encoder register counts A/B edges
  bool diagnostic_feedback = false;      // the encoder register counts the axis' own steps
  bool step_dir_output = false;          // false: CW/CCW pulse outputs
  bool backplane_proximity = false;      // the proximity bit of the command words is used
  HomingVariant homing = HomingVariant::kSwitch;
  std::int32_t starting_speed = 0;  // Vs, steps/s
  // The 3602's and 3202's settings. The 3601 dialect leaves them at these values, which are the
  // 3601's fixed behaviour; the shared axis does not act on other values yet (the 3602 and 3202
  // issues add that behaviour together with their dialects).
  Nanos homing_timeout = 0;  // 0 = none (3602: 0 ... 300 s, expiry -> Home Invalid, A16)
  LimitFunction cw_input = LimitFunction::kLimit;
  LimitFunction ccw_input = LimitFunction::kLimit;
  bool disabled = false;  // 3602 / 3202: the axis ignores commands

  bool used(InputLine l) const noexcept { return (inputs_used >> static_cast<unsigned>(l)) & 1u; }
};

}  // namespace stepmod::module::axis

#pragma once
// The decoded status of one axis/channel: named flags and registers, whatever module reports
// them. The shared axis code produces it; a dialect (module/m3601/...) writes it into its status
// words.
#include <cstdint>

namespace stepmod::module::axis {

// Status and error latches, named as in the manuals. The axis' own (AxisState::latches()) are
// written by the table of transitions only.
struct Latches {
  bool hold = false;
  bool stopped = false;
  bool at_home = false;
  bool move_complete = false;
  bool home_invalid = false;
  bool invalid_profile = false;
  bool position_invalid = false;
  bool input_error = false;
  bool command_error = false;
  bool configuration_error = false;
};

// The latches as reported, but for `stopped`: already filtered, never with MC, At Home or Hold
// on event modules (Axis::status()).
struct AxisStatus : Latches {
  bool configuration_mode = false;
  // Motion: direction of the pulses being output, ramp phase.
  bool moving_cw = false;
  bool moving_ccw = false;
  bool accelerating = false;
  bool decelerating = false;
  // Inputs and feature states.
  std::uint16_t inputs_active = 0;  // bit n = InputLine n active (unused inputs read 0, A27)
  bool proximity_echo = false;      // the backplane proximity bit, echoed
  bool follower_mode = false;
  bool blend_running = false;
  bool blend_acknowledge = false;
  bool min_registration_set = false;
  // Registers.
  std::int64_t position = 0;
  std::int64_t encoder = 0;
  std::int64_t capture = 0;
};

}  // namespace stepmod::module::axis

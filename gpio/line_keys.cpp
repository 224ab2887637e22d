// Config-file keys of the lines (docs/interface.md section 2); also the VCD wire suffixes (5).
#include "gpio/backend.hpp"
#include "gpio/line_options.hpp"

namespace stepmod::gpio {

std::string_view input_key(InputLine l) noexcept {
  switch (l) {
    case InputLine::kCapture:
      return "capture";
    case InputLine::kExternal:
      return "external";
    case InputLine::kHome:
      return "home";
    case InputLine::kEStop:
      return "estop";
    case InputLine::kCwLimit:
      return "cw_limit";
    case InputLine::kCcwLimit:
      return "ccw_limit";
    case InputLine::kEncA:
      return "enc_a";
    case InputLine::kEncB:
      return "enc_b";
    case InputLine::kEncZ:
      return "enc_z";
  }
  return "?";
}

std::string_view output_key(OutputLine l) noexcept {
  switch (l) {
    case OutputLine::kStep:
      return "step";
    case OutputLine::kDir:
      return "dir";
    case OutputLine::kGpo:
      return "gpo";
  }
  return "?";
}

std::string_view bias_name(Bias b) noexcept {
  switch (b) {
    case Bias::kAsIs:
      return "as-is";
    case Bias::kPullUp:
      return "pull-up";
    case Bias::kPullDown:
      return "pull-down";
    case Bias::kDisabled:
      return "disabled";
  }
  return "?";
}

std::string_view drive_name(Drive d) noexcept {
  switch (d) {
    case Drive::kPushPull:
      return "push-pull";
    case Drive::kOpenDrain:
      return "open-drain";
    case Drive::kOpenSource:
      return "open-source";
  }
  return "?";
}

}  // namespace stepmod::gpio

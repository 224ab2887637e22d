// Config-file keys of the lines (INTERFACE.md section 2); also the VCD wire suffixes (section 5).
#include "gpio/backend.hpp"

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

}  // namespace stepmod::gpio

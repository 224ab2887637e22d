#pragma once
// Line ids of one axis, shared by every layer: the planner schedules edges on output lines, the
// pulse thread and the GPIO backends write them, the module reads input lines, the VCD trace and
// the simulator panel name both. The orders are fixed by docs/interface.md section 4 (panel bits).
#include <cstdint>

namespace stepmod {

// Output lines of one axis, in the order of the simulator panel's "output levels" bits.
enum class OutputLine : std::uint8_t { kStep = 0, kDir = 1, kGpo = 2 };
inline constexpr unsigned kOutputLinesPerAxis = 3;

// Input lines of one axis. The first six are in the order of the simulator panel's force bits
// (docs/interface.md section 4): 0 capture, 1 external, 2 home, 3 E-stop, 4 CW limit, 5 CCW limit.
enum class InputLine : std::uint8_t {
  kCapture = 0,
  kExternal = 1,
  kHome = 2,
  kEStop = 3,
  kCwLimit = 4,
  kCcwLimit = 5,
  kEncA = 6,
  kEncB = 7,
  kEncZ = 8,
};
inline constexpr unsigned kInputLinesPerAxis = 9;
inline constexpr unsigned kPanelInputs = 6;  // inputs the simulator panel can force

}  // namespace stepmod

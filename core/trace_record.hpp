#pragma once
// One line change for the VCD trace (docs/interface.md section 5): an output written by the pulse
// thread (at the time it was written) or an input edge (at the time it was stamped).
#include <cstdint>

#include "core/clock.hpp"

namespace stepmod {

struct TraceRecord {
  Nanos t = 0;
  std::uint8_t axis = 0;
  std::uint8_t line = 0;  // OutputLine or InputLine value, per `is_input`
  std::uint8_t level = 0;
  std::uint8_t is_input = 0;
};

}  // namespace stepmod

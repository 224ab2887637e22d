#pragma once
// The two status words of one axis of a 16-bit module (3601, 3602: status MSW and LSW), as a PLC
// program tests them. Each dialect's Status (module_types/mXXXX/plc_status_XXXX.hpp) adds its
// registers; `MovingBits` are its status MSW's Moving CW and Moving CCW bits.
#include <cstdint>

namespace stepmod::plc {

template <std::uint16_t MovingBits>
struct StatusWords16 {
  std::uint16_t msw = 0;
  std::uint16_t lsw = 0;

  bool has(std::uint16_t msw_bit) const { return (msw & msw_bit) != 0; }
  bool has_lsw(std::uint16_t lsw_bit) const { return (lsw & lsw_bit) != 0; }
  // "Pulses being output" (Moving CW or CCW).
  bool moving() const { return has(MovingBits); }
};

}  // namespace stepmod::plc

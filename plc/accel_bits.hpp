#pragma once
// The acceleration type's command bits, looked up by name in a manual's command table: the three
// manuals name the two S-curve bits alike (3601/3602 command LSW, 3202 command DINT).
#include <string_view>

#include "core/bit_table.hpp"
#include "plc/profile.hpp"

namespace stepmod::plc {

template <typename Word, typename Table>
constexpr Word accel_bits_in(const Table& t, AccelType type) noexcept {
  constexpr std::string_view kSCurve = "S-Curve Acceleration (0 = constant)";
  constexpr std::string_view kTrapezoidal = "Trapezoidal S-Curve (0 = triangular)";
  Word bits = 0;
  for (const NamedBit& b : t) {
    const bool s_curve = b.name == kSCurve && type != AccelType::kConstant;
    const bool trapezoidal = b.name == kTrapezoidal && type == AccelType::kTrapezoidalS;
    if (s_curve || trapezoidal) bits = static_cast<Word>(bits | (Word{1} << b.bit));
  }
  return bits;
}

}  // namespace stepmod::plc

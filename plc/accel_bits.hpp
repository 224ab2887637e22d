#pragma once
// The acceleration type's command bits, looked up by name in a manual's command table: the three
// manuals name the two S-curve bits alike (3601/3602 command LSW, 3202 command DINT).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/bit_table.hpp"
#include "plc/move_profile.hpp"

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

// The segments' acceleration types as two-bit codes (low bit S-curve, high bit trapezoidal: the
// command LSW's code), segments 1..8 in `lo`, 9..16 in `hi`: the 16-bit modules' first blend block
// (3601 manual ch. 5, 3602 manual ch. 9). `code` is the dialect's accel_bits.
struct TypePairs {
  std::uint16_t lo = 0;
  std::uint16_t hi = 0;
};
template <typename Code>
TypePairs segment_type_pairs(const BlendProfile& b, Code code) {
  TypePairs p;
  for (std::size_t i = 0; i < b.segments.size() && i < 16; ++i) {
    const std::uint16_t bits = code(b.segments[i].type);
    std::uint16_t& word = i < 8 ? p.lo : p.hi;
    word = static_cast<std::uint16_t>(word | bits << (2 * (i % 8)));
  }
  return p;
}

}  // namespace stepmod::plc

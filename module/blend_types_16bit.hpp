#pragma once
// The acceleration types of a first blend block, which the 3601 and 3602 manuals encode alike
// (3601 manual ch. 5, 3602 manual table 9.2): segment n's two-bit type pair in one of two words
// (segments 1..8, 9..16; segment 1 or 9 in bits 1:0), the final deceleration's type in bits 15-14
// of its word. Shared by those two dialects only; each still reads its own words (where the pairs
// and the final deceleration sit, and what else the final deceleration word holds).
#include <cstdint>

#include "core/module_shape.hpp"
#include "module/axis/axis_command.hpp"

namespace stepmod::module {

inline void decode_blend_types_16bit(const ImageWords& out, unsigned pairs_1_to_8_word,
                                     unsigned pairs_9_to_16_word, unsigned final_decel_word,
                                     axis::BlendFirstBlock& b) noexcept {
  for (unsigned n = 1; n <= b.shapes.size(); ++n) {
    const auto w =
        static_cast<std::uint16_t>(out.w[n <= 8 ? pairs_1_to_8_word : pairs_9_to_16_word]);
    const unsigned pair = (w >> (2 * ((n - 1) % 8))) & 0x3u;
    // A22: the low bit selects S-curve; binary 10 (low bit 0) reads as constant, as the manuals'
    // general rule "least significant bit reset => constant" says (the 3602 refuses such a pair
    // separately, 3602-IP-07).
    b.shapes[n - 1] = !(pair & 0x1u)  ? planner::AccelShape::kConstant
                      : (pair & 0x2u) ? planner::AccelShape::kTrapezoidalS
                                      : planner::AccelShape::kTriangularS;
  }
  switch (static_cast<std::uint16_t>(out.w[final_decel_word]) >> 14) {
    case 0b00:
      b.final_shape = planner::AccelShape::kConstant;
      break;
    case 0b01:
      b.final_shape = planner::AccelShape::kTriangularS;
      break;
    case 0b11:
      b.final_shape = planner::AccelShape::kTrapezoidalS;
      break;
    default:
      b.final_shape.reset();  // 10: invalid for the final deceleration (3601-IP-19, A22; 3602 4.5)
      break;
  }
}

// A segment block (3601 manual ch. 5, 3602 manual table 9.22): words 2-3 the length, 4-5 the
// speed, 6 the rate, as the command words decode them; `word7_zero`: the unused word 7 is 0.
inline axis::BlendSegmentBlock blend_segment_16bit(const axis::AxisCommand& c,
                                                   bool word7_zero) noexcept {
  return {c.target, c.speed, c.accel, word7_zero};
}

}  // namespace stepmod::module

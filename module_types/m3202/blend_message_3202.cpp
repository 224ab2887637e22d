#include "module_types/m3202/blend_message_3202.hpp"

namespace stepmod::module::m3202 {

BlendMessage blend_message_from_dints(std::span<const std::int32_t> data) noexcept {
  auto dint = [data](unsigned i) -> std::int32_t { return i < data.size() ? data[i] : 0; };
  BlendMessage m;
  m.channel = dint(msg_dint::kChannel);
  m.first.segments = dint(msg_dint::kSegments);
  const auto pairs = static_cast<std::uint32_t>(dint(msg_dint::kTypePairs));
  for (unsigned n = 1; n <= m.first.shapes.size(); ++n) {
    const unsigned pair = (pairs >> (2 * (n - 1))) & 0x3u;
    // A22 (same pair code as the 3601's, 3601 manual ch. 5): the low bit selects S-curve; binary 10
    // is constant.
    m.first.shapes[n - 1] = !(pair & 0x1u)  ? planner::AccelShape::kConstant
                            : (pair & 0x2u) ? planner::AccelShape::kTrapezoidalS
                                            : planner::AccelShape::kTriangularS;
  }
  const auto final_word = static_cast<std::uint32_t>(dint(msg_dint::kFinalDecel));
  switch (final_word >> 30) {
    case 0b00:
      m.first.final_shape = planner::AccelShape::kConstant;
      break;
    case 0b01:
      m.first.final_shape = planner::AccelShape::kTriangularS;
      break;
    case 0b11:
      m.first.final_shape = planner::AccelShape::kTrapezoidalS;
      break;
    default:
      break;  // 3202-IP-17: type 10 is invalid for the final deceleration
  }
  // 3202 manual ch. 5 (inferred): the value is bits 29-0, steps/s^2 (A31).
  m.first.final_decel = static_cast<std::int64_t>(final_word & 0x3FFF'FFFFu);
  for (unsigned n = 0; n < m.segments.size(); ++n) {
    const unsigned base = msg_dint::kFirstSegment + msg_dint::kPerSegment * n;
    axis::BlendSegmentBlock& s = m.segments[n];
    s.length = dint(base);
    const std::int32_t speed = dint(base + 1);
    if (speed >= 0) s.speed = speed;
    s.rate = dint(base + 2);
  }
  return m;
}

}  // namespace stepmod::module::m3202

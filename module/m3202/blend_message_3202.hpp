#pragma once
// The 3202's 52-DINT blend profile message (3202 manual Ch.5 "Blend Move Programming", digest
// 5.8), as it arrives through the image's message mailbox (INTERFACE.md 3, offsets 192..415),
// decoded into the shared axis' blend blocks. The checks are the axis' (Blend::program).
#include <array>
#include <cstdint>
#include <span>

#include "module/axis/axis_command.hpp"

namespace stepmod::module::m3202 {

// DINT indices of the message (digest 5.8).
namespace msg_dint {
inline constexpr unsigned kChannel = 0;       // 1 or 2
inline constexpr unsigned kSegments = 1;      // 2 ... 16
inline constexpr unsigned kTypePairs = 2;     // segment n: bits 2n-1 : 2n-2
inline constexpr unsigned kFinalDecel = 3;    // type in bits 31-30, value in 29-0
inline constexpr unsigned kFirstSegment = 4;  // length, speed, rate per segment
inline constexpr unsigned kPerSegment = 3;
inline constexpr unsigned kCount = 52;
}  // namespace msg_dint

// The message result written to the mailbox (INTERFACE.md 3: 0 accepted, otherwise the error is
// reported in the status bits as the manual says).
inline constexpr std::int32_t kMessageAccepted = 0;
inline constexpr std::int32_t kMessageRefused = 1;

struct BlendMessage {
  std::int32_t channel = 0;  // as written: 1 or 2 are channels
  axis::BlendFirstBlock first;
  std::array<axis::BlendSegmentBlock, 16> segments{};
};

// Decodes the 52 DINTs; `data` shorter than 52 reads the missing DINTs as 0.
BlendMessage blend_message_from_dints(std::span<const std::int32_t> data) noexcept;

}  // namespace stepmod::module::m3202

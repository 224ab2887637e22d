#pragma once
// The 3202's 52-DINT blend profile message (3202 manual Ch.5 "Blend Move Programming"), as it
// arrives through the image's message mailbox (docs/interface.md 3, offsets 192..415), decoded into
// the shared axis' blend blocks. The checks are the axis' (Blend::program).
#include <array>
#include <cstdint>
#include <span>

#include "module/axis/axis_command.hpp"
#include "module_types/m3202/words_3202.hpp"

namespace stepmod::module::m3202 {
using namespace words::m3202;  // this module's words: module_types/m3202/words_3202.hpp

struct BlendMessage {
  std::int32_t channel = 0;  // as written: 1 or 2 are channels
  axis::BlendFirstBlock first;
  std::array<axis::BlendSegmentBlock, 16> segments{};
};

// Decodes the 52 DINTs; `data` shorter than 52 reads the missing DINTs as 0.
BlendMessage blend_message_from_dints(std::span<const std::int32_t> data) noexcept;

}  // namespace stepmod::module::m3202

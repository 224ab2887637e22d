#pragma once
// The 3202 dialect: the only code that knows the 3202's DINT indices and bit positions
// (words_3202.hpp names them). One channel at a time: channel 0 uses DINTs 0..7, channel 1
// DINTs 8..15 (3202 manual). Command DINTs -> AxisCommand, AxisStatus -> status DINTs, the
// configuration-mode image. Configuration DINTs -> AxisConfig is config_3202.hpp.
#include <cstdint>

#include "core/module_shape.hpp"
#include "module/axis/axis_command.hpp"
#include "module/axis/axis_status.hpp"
#include "module_types/m3202/words_3202.hpp"

namespace stepmod::module::m3202 {
using namespace words::m3202;  // this module's words: module_types/m3202/words_3202.hpp

// Command mode output DINTs of `channel` (3202 manual ch. 5), word-level rules included.
axis::AxisCommand command_from_words(const ImageWords& out, unsigned channel) noexcept;

// Command mode input DINTs of `channel` (3202 manual ch. 6). `disabled`: bit 28.
void status_to_words(const axis::AxisStatus& s, bool disabled, unsigned channel,
                     ImageWords& in) noexcept;

// Configuration mode input DINTs of `channel` (3202 manual ch. 3): DINT 0 mirrors the accepted
// configuration bits (A26: only accepted data) with CfgE (13), disabled (28), Module OK (30) and
// the mode bit (31); DINT 1 the starting speed; DINT 3 the firmware revision.
struct ConfigMirror {
  std::uint32_t bits = 0;
  std::int32_t starting_speed = 0;
};
void configuration_image_to_words(const ConfigMirror& mirror, bool configuration_error,
                                  bool disabled, unsigned channel, ImageWords& in) noexcept;

}  // namespace stepmod::module::m3202

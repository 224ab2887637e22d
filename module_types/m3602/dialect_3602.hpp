#pragma once
// The 3602 dialect: the only code that knows the 3602's word indices, bit positions and the
// binary split of its 32-bit values (words_3602.hpp names them; 3602 manual Ch.9 "Multi-Word
// Parameters", Tables 9.2-9.27). Works on one axis' eight words (b+0 .. b+7 moved to 0..7);
// module_3602 splits and joins the image. Configuration words -> AxisConfig is config_3602.hpp.
#include <cstdint>
#include <optional>

#include "core/module_shape.hpp"
#include "module/axis/axis_command.hpp"
#include "module/axis/axis_status.hpp"
#include "module_types/m3602/interpolated_command.hpp"
#include "module_types/m3602/words_3602.hpp"

namespace stepmod::module::m3602 {
using namespace words::m3602;  // this module's words: module_types/m3602/words_3602.hpp

// Command mode output words of one axis (3602 manual Tables 9.2-9.22), word-level rules included:
// reserved words or LSW bits that must be 0 for the one command set (3602-CE-10), any command with
// interpolation bits (3602-CE-03) set AxisCommand::words_invalid.
axis::AxisCommand command_from_words(const ImageWords& out) noexcept;

// The interpolated move block in all sixteen output words of the module (3602 manual
// Tables 9.23-9.26; `out` is the whole image, word 0 = axis 1's MSW): nullopt when axis 1's command
// LSW bits 9..14 are all 0 (no interpolated command), else the decoded command with its word-level
// fault.
std::optional<InterpolatedCommand> interpolated_from_words(const ImageWords& out) noexcept;

// Whether the command LSW asks for the general-purpose output on (bit 7, a level).
bool gpo_from_words(const ImageWords& out) noexcept;

// What the status words say besides the shared axis' status.
struct StatusExtras {
  bool axis_enabled = false;   // 3602-EN-01: configured and not disabled
  bool interpolating = false;  // 3602-LSW-01: axis 1 runs an interpolated move (LSW bit 11)
  bool gpo = false;            // 3602-LSW-01: echo of command LSW bit 7
};

// Command mode input words of one axis (3602 manual Table 9.27, "Status Bits MSW/LSW"). Position
// and capture are int32 that roll over at +-2^31 (Table 9.27).
void status_to_words(const axis::AxisStatus& s, const StatusExtras& x, ImageWords& in) noexcept;

// Configuration mode input words (3602 manual Table 8.5): A26, the 3602 echoes the last data
// written (config MSW bits 0..12, LSW, starting speed, homing timeout); bit 13 CfgE, 14 axis
// enabled, 15 mode.
void configuration_image_to_words(const ImageWords& out, bool configuration_error,
                                  bool axis_enabled, ImageWords& in) noexcept;

// One 32-bit value in the binary split (3602 manual Ch.9 "Multi-Word Parameters"): the reported
// registers roll over at +-2^31.
std::int32_t wrap_to_int32(std::int64_t v) noexcept;

}  // namespace stepmod::module::m3602

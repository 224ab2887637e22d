#pragma once
// The 3601 dialect: the only code that knows the 3601's word indices, bit positions and number
// encodings (words_3601.hpp names them). Every translation between the 3601's eight words and
// the shared axis' decoded values happens here (model: libgpiod's *_from_uapi / *_to_uapi):
// command words -> AxisCommand, AxisStatus -> status words, the configuration-mode image.
// Configuration words -> AxisConfig is config_3601.hpp.
#include <array>
#include <cstdint>

#include "core/module_shape.hpp"
#include "module/axis/axis_command.hpp"
#include "module/axis/axis_status.hpp"
#include "module_types/m3601/words_3601.hpp"

namespace stepmod::module::m3601 {
using namespace words::m3601;  // this module's words: module_types/m3601/words_3601.hpp

// Command mode output words 0..7 (3601 manual ch. 5), word-level rules included: a word or the
// command LSW that must be 0 for the one command set (3601-CE-09, CE-15, CE-21) or for the
// minimum-registration store (3601 manual ch. 4) sets AxisCommand::words_invalid.
axis::AxisCommand command_from_words(const ImageWords& out) noexcept;

// Command mode input words 0..7 (3601 manual ch. 6).
void status_to_words(const axis::AxisStatus& s, ImageWords& in) noexcept;

// Configuration mode input words (3601 manual ch. 3): words 0..3 mirror the accepted configuration
// (A26: only accepted data), word 0 also carries CfgE, Module OK and the mode bit; words 6/7 the
// firmware revision.
using ConfigMirror = std::array<std::uint16_t, 4>;
void configuration_image_to_words(const ConfigMirror& mirror, bool configuration_error,
                                  ImageWords& in) noexcept;

}  // namespace stepmod::module::m3601

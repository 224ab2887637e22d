#pragma once
// The words a PLC program writes to one axis of a 3602 (3602 manual tables 8.1, 9.2), as pure
// functions: no I/O, so the tests can compare them word for word. Bit positions come from the
// module's table (module_types/m3602/words_3602.hpp); 32-bit numbers use the binary split (3602 manual ch. 9).
// Each axis owns eight of the sixteen output words, from b = 8 * axis (axis 0 = the manual's axis
// 1).
#include <array>
#include <cstdint>
#include <vector>

#include "core/module_shape.hpp"
#include "plc/move_profile.hpp"

namespace stepmod::plc::m3602 {

// The first output word of `axis` (0 or 1).
unsigned base(unsigned axis);
// Writes a binary-split value into words `index` and `index + 1` (relative to `b`).
void put_split(ImageWords& w, unsigned b, unsigned index, std::int32_t value);
// Command mode words of one axis into `w` (the other axis' words are left alone): MSW and LSW as
// given, words 2/3 and 4/5 binary-split, 6 and 7 as given.
void put_command(ImageWords& w, unsigned axis, std::uint16_t msw, std::uint16_t lsw,
                 std::int32_t w23, std::int32_t w45, std::int16_t w6, std::int16_t w7);
// Configuration words of one axis into `w`: config bits MSW (the mode bit is added), active
// levels LSW, starting speed (binary split), homing timeout in s; words 5..7 zero.
void put_configuration(ImageWords& w, unsigned axis, std::uint16_t cfg_msw, std::uint16_t cfg_lsw,
                       std::int32_t start_speed, std::int16_t homing_timeout_s);
// Command LSW bits 0/1 for an acceleration type; the same code is a blend type pair.
std::uint16_t accel_bits(AccelType t);

// Eight words of one axis, indexed relative to its base (word 0 = command MSW).
using AxisWords = std::array<std::int32_t, 8>;
// Writes `a` into the axis' words of `w` (the other axis' words are left alone).
void put_axis(ImageWords& w, unsigned axis, const AxisWords& a);

// The blend programming blocks (3602 manual tables 9.2, 9.21, 9.22): the first block (segment
// count, type pairs of segments 9..16 / 1..8 in words 3 / 4, final deceleration type in bits 15..14
// and value in bits 10..0 of word 5) and one per segment (length 2/3, speed 4/5, rate 6). Words 0
// and 1 are 0: the handshake bits are the sequencer's.
std::vector<AxisWords> blend_blocks(const BlendProfile& b);

}  // namespace stepmod::plc::m3602

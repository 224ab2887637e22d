#pragma once
// The words a PLC program writes to one axis of a 3602 (digest 4.1, 4.5), as pure functions: no
// I/O, so the tests can compare them word for word. Bit positions come from the module's table
// (module/m3602/words_3602.hpp); 32-bit numbers use the binary split (digest 2.2). Each axis owns
// eight of the sixteen output words, from b = 8 * axis (axis 0 = the manual's axis 1).
#include <cstdint>

#include "core/module_shape.hpp"
#include "plc/profile.hpp"

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
// Command LSW bits 0/1 for an acceleration type.
std::uint16_t accel_bits(AccelType t);

}  // namespace stepmod::plc::m3602

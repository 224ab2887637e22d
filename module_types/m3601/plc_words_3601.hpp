#pragma once
// The words a PLC program writes to a 3601 (3601 manual ch. 3, 5), as pure functions: no I/O,
// so the tests can compare them word for word. Bit positions come from the module's table
// (module_types/m3601/words_3601.hpp); numbers use the decimal split (3601 manual ch. 5).
#include <cstdint>
#include <vector>

#include "core/module_shape.hpp"
#include "plc/move_profile.hpp"

namespace stepmod::plc::m3601 {

// Command mode: word 0 and 1 as given, words 2/3 and 4/5 decimal-split, 6 and 7 as given.
ImageWords command_words(std::uint16_t msw, std::uint16_t lsw, std::int32_t w23, std::int32_t w45,
                         std::int16_t w6, std::int16_t w7);
// Configuration mode: config bits MSW (the mode bit is added), active levels LSW, starting speed.
ImageWords configuration_words(std::uint16_t cfg_msw, std::uint16_t cfg_lsw,
                               std::int32_t start_speed);
// Writes a decimal-split value into words `msw_index` and `msw_index + 1`.
void put_split(ImageWords& w, unsigned msw_index, std::int64_t value);
// Speed (4/5), acceleration (6) and deceleration (7) of `p`.
void put_profile(ImageWords& w, const Profile& p);

// Encoder follower (3601 manual ch. 4, 5): `msw` the level-held direction bit (Manual CW = same
// sense, Manual CCW = reverse, 0 = follower mode without motion), `lsw` normally just the
// follower bit; multiplier and divisor are plain integers in words 2 and 3 (not split), words
// 4/5 must be 0, accel/decel in 6/7.
ImageWords follower_words(std::uint16_t msw, std::int16_t multiplier, std::int16_t divisor,
                          std::int16_t accel, std::int16_t decel, std::uint16_t lsw);

// Command LSW bits 0/1 for an acceleration type; the same code is a blend type pair.
std::uint16_t accel_bits(AccelType t);

// The blend programming blocks (3601 manual ch. 5): the first block (segment count, type pairs,
// final deceleration) and one per segment; word 0 and the LSW handshake bits are the sequencer's.
std::vector<ImageWords> blend_blocks(const BlendProfile& b);

}  // namespace stepmod::plc::m3601

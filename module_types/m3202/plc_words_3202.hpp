#pragma once
// The DINTs a PLC program writes to one 3202 channel (3202 manual ch. 3, 5), as pure functions: no
// I/O, so the tests can compare them word for word. Bit positions come from the module's table
// (module_types/m3202/words_3202.hpp); numbers are native DINTs (3202 manual ch. 5).
#include <array>
#include <cstdint>

#include "plc/move_profile.hpp"

namespace stepmod::plc::m3202 {

// The eight DINTs of one channel (channel 1: image words 0..7, channel 2: 8..15).
using ChannelWords = std::array<std::int32_t, 8>;

// Command mode: the command word as given, target, speed, accel and decel (steps/s^2, A31);
// DINTs 5..7 reserved, 0.
ChannelWords command_words(std::uint32_t command, std::int32_t target, std::int32_t speed,
                           std::int32_t accel, std::int32_t decel);
// Configuration mode: configuration bits (the mode bit 31 is added) and starting speed.
ChannelWords configuration_words(std::uint32_t bits, std::int32_t start_speed);

// Command word bits 16/17 for an acceleration type (3202 manual ch. 5); the same code is a blend
// type pair (3202 manual ch. 5).
std::uint32_t accel_bits(AccelType t);

// The 52-DINT blend profile message for `channel_number` (the manual's 1 or 2; anything else is
// written as given, for tests of the module's refusal). Rates are steps/s^2 on the 3202 (A31).
std::array<std::int32_t, 52> blend_message(std::int32_t channel_number, const BlendProfile& b);

}  // namespace stepmod::plc::m3202

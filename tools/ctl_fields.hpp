#pragma once
// The pieces every module's status display (tools/ctl_status_XXXX.cpp) is written with: a
// word in hex, one named field with its state, all fields of a word.
#include <cstdint>
#include <sstream>
#include <string>

#include "core/bit_table.hpp"

namespace stepmod::tools::ctl {

// The low 16 bits of a sign-extended word.
std::uint16_t u16(std::int32_t w);
// `v` in `digits` upper-case hex digits.
std::string hex(std::uint32_t v, unsigned digits);
// One field with its state: "    1  bit 12  Command Error".
void one_field(std::ostringstream& o, std::uint32_t word, const NamedBit& b);
// Every named field with its state, so that "not set" is visible too (a person debugging a PLC
// program wants to see the zero as much as the one).
void all_bits(std::ostringstream& o, std::uint32_t word, BitTable table);

}  // namespace stepmod::tools::ctl

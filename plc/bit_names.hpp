#pragma once
// Status decoding for people: the names of a word's set bits, from a dialect's bit table.
#include <cstdint>
#include <string>

#include "core/bit_table.hpp"

namespace stepmod::plc {

// Names of the set fields of `word`, comma-separated ("-" when none). A field wider than one bit
// shows as "name=value".
std::string set_bit_names(std::uint32_t word, BitTable table);

// The value of `field` in `word`.
constexpr std::uint32_t field_value(std::uint32_t word, const NamedBit& field) {
  return (word >> field.bit) & ((1u << field.width) - 1u);
}

}  // namespace stepmod::plc

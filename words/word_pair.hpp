#pragma once
// Two 16-bit backplane words holding one 32-bit number, as the PLC sees them (signed INTs): the
// 3601's and 3602's number encodings (module_types/m3601/words_3601.hpp, module_types/m3602/words_3602.hpp) produce these.
#include <cstdint>

namespace stepmod::words {

struct WordPair {
  std::int16_t msw = 0;
  std::int16_t lsw = 0;
  bool operator==(const WordPair&) const = default;
};

// The PLC's words are 16-bit INTs; callers pass them sign-extended, but a raw 0..65535 value must
// mean the same word, so only the low 16 bits are looked at.
constexpr std::int32_t as_int16(std::int32_t w) noexcept {
  return static_cast<std::int16_t>(static_cast<std::uint16_t>(w & 0xFFFF));
}

}  // namespace stepmod::words

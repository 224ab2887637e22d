// The 3602's number encoding (binary split), declared in module_types/m3602/words_3602.hpp.
#include "module_types/m3602/words_3602.hpp"

namespace stepmod::words {

std::int32_t decode_3602(std::int32_t msw, std::int32_t lsw) noexcept {
  const std::uint32_t u = (static_cast<std::uint32_t>(msw) & 0xFFFFu) << 16 |
                          (static_cast<std::uint32_t>(lsw) & 0xFFFFu);
  return static_cast<std::int32_t>(u);
}

WordPair encode_3602(std::int32_t value) noexcept {
  const auto u = static_cast<std::uint32_t>(value);
  return {static_cast<std::int16_t>(static_cast<std::uint16_t>(u >> 16)),
          static_cast<std::int16_t>(static_cast<std::uint16_t>(u & 0xFFFFu))};
}

}  // namespace stepmod::words

// The 3601's number encoding (decimal split), declared in module_types/m3601/words_3601.hpp.
#include "module_types/m3601/words_3601.hpp"

namespace stepmod::words {

std::optional<std::int32_t> decode_3601(std::int32_t msw, std::int32_t lsw) noexcept {
  const std::int32_t m = as_int16(msw);
  const std::int32_t l = as_int16(lsw);
  if (l > 999 || l < -999) return std::nullopt;
  if ((m > 0 && l < 0) || (m < 0 && l > 0)) return std::nullopt;
  return m * 1000 + l;
}

std::optional<std::int32_t> decode_3601_unsigned(std::int32_t msw, std::int32_t lsw) noexcept {
  const std::int32_t m = as_int16(msw);
  const std::int32_t l = as_int16(lsw);
  if (m < 0 || l < 0 || l > 999) return std::nullopt;
  return m * 1000 + l;
}

std::int64_t decode_3601_report(std::int32_t msw, std::int32_t lsw) noexcept {
  return static_cast<std::int64_t>(as_int16(msw)) * 1000 + as_int16(lsw);
}

WordPair encode_3601(std::int64_t value) noexcept {
  const std::int64_t q = value / 1000;  // C++ division truncates toward zero, as the manual wants
  const std::int64_t r = value - q * 1000;
  return {static_cast<std::int16_t>(static_cast<std::uint16_t>(q & 0xFFFF)),
          static_cast<std::int16_t>(r)};
}

}  // namespace stepmod::words

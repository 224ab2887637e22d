#include "ipc/codec.hpp"

namespace stepmod::ipc::codec {
namespace {
// The PLC's words are 16-bit INTs; callers pass them sign-extended, but a raw 0..65535 value must
// mean the same word, so only the low 16 bits are looked at.
std::int32_t as_int16(std::int32_t w) noexcept {
  return static_cast<std::int16_t>(static_cast<std::uint16_t>(w & 0xFFFF));
}
}  // namespace

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

}  // namespace stepmod::ipc::codec

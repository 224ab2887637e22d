#pragma once
// The manuals' encodings of 32-bit numbers in backplane words (digest MODULES.md section 2).
// Words are passed as the sign-extended int32 values of ImageWords; only their low 16
// bits count for the 16-bit modules.
#include <cstdint>
#include <optional>

namespace stepmod::ipc::codec {

// Two 16-bit words as the PLC sees them (signed INTs).
struct WordPair {
  std::int16_t msw = 0;
  std::int16_t lsw = 0;
  bool operator==(const WordPair&) const = default;
};

// ---- 3601: decimal (thousands) split, digest 2.1 -------------------------------------------
// value = MSW * 1000 + LSW. Valid when |LSW| <= 999 and the words do not have opposite signs
// (either may be 0). nullopt = the module answers with a Command Error.
std::optional<std::int32_t> decode_3601(std::int32_t msw, std::int32_t lsw) noexcept;
// Parameters that cannot be negative (speeds, Vs, segment length, registration distance):
// MSW >= 0 and LSW 0..999.
std::optional<std::int32_t> decode_3601_unsigned(std::int32_t msw, std::int32_t lsw) noexcept;
// Reported registers (position, encoder, capture): MSW*1000 + LSW without validity rules. A value
// whose thousands wrapped in the MSW (A9) reads back modulo 65,536,000.
std::int64_t decode_3601_report(std::int32_t msw, std::int32_t lsw) noexcept;
// q = trunc(value / 1000) toward zero, r = value - 1000 q; MSW = q wrapped to 16 bits (A9: the
// module reports thousands beyond +-32,767 by letting the MSW wrap, 7FFFh -> 8000h).
WordPair encode_3601(std::int64_t value) noexcept;

// ---- 3602: binary split, digest 2.2 ---------------------------------------------------------
std::int32_t decode_3602(std::int32_t msw, std::int32_t lsw) noexcept;
WordPair encode_3602(std::int32_t value) noexcept;

// ---- 3202: native DINT, digest 2.3 ----------------------------------------------------------
inline std::int32_t decode_3202(std::int32_t w) noexcept {
  return w;
}
inline std::int32_t encode_3202(std::int32_t v) noexcept {
  return v;
}

}  // namespace stepmod::ipc::codec

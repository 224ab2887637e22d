#pragma once
// How the 3601 reads its command parameters: ranges, units and the S-curve bits (3601 manual
// Ch.5 "Command Mode Output Data"; digest 3.5, 3.7, 7.1). Shared by every command file.
#include <cstdint>
#include <optional>

#include "ipc/codec.hpp"
#include "module/m3601/words_3601.hpp"
#include "module/personality.hpp"
#include "planner/motion_request.hpp"

namespace stepmod::module::m3601 {

inline constexpr std::int32_t kMinTarget = -8'388'608;
inline constexpr std::int32_t kMaxTarget = 8'388'607;
inline constexpr std::int32_t kMaxSpeed = 1'000'000;
inline constexpr std::int32_t kMinRate = 1;     // steps/ms/s
inline constexpr std::int32_t kMaxRate = 2000;  // steps/ms/s

// Accel/decel words are steps/ms/s; the planner works in steps/s^2 (digest 7.1).
inline double rate_from_word(std::int32_t steps_per_ms_per_s) {
  return steps_per_ms_per_s * 1000.0;
}

// Command LSW bits 0/1: constant, triangular S or trapezoidal S.
inline planner::AccelShape shape_from_lsw(std::uint16_t lsw) {
  if (!(lsw & cmd_lsw::kSCurve)) return planner::AccelShape::kConstant;
  return (lsw & cmd_lsw::kTrapezoidalS) ? planner::AccelShape::kTrapezoidalS
                                        : planner::AccelShape::kTriangularS;
}

inline bool rate_in_range(std::int32_t v) {
  return v >= kMinRate && v <= kMaxRate;
}

// Words 2-3: target position / preset value / registration count (decimal split; nullopt for an
// LSW outside -999..999 or words of opposite signs).
inline std::optional<std::int32_t> target_words(const ImageWords& out) {
  return ipc::codec::decode_3601(out.w[out_word::kTargetMsw], out.w[out_word::kTargetLsw]);
}

// Words 4-5: programmed speed (decimal split, never negative).
inline std::optional<std::int32_t> speed_words(const ImageWords& out) {
  return ipc::codec::decode_3601_unsigned(out.w[out_word::kSpeedMsw], out.w[out_word::kSpeedLsw]);
}

}  // namespace stepmod::module::m3601

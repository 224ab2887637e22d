#include "plc/words_3602.hpp"

#include "ipc/codec.hpp"
#include "module/m3602/words_3602.hpp"

namespace stepmod::plc::m3602 {

namespace m = module::m3602;

unsigned base(unsigned axis) {
  return m::kWordsPerAxis * axis;
}

void put_split(ImageWords& w, unsigned b, unsigned index, std::int32_t value) {
  const auto p = ipc::codec::encode_3602(value);
  w.w[b + index] = p.msw;
  w.w[b + index + 1] = p.lsw;
}

void put_command(ImageWords& w, unsigned axis, std::uint16_t msw, std::uint16_t lsw,
                 std::int32_t w23, std::int32_t w45, std::int16_t w6, std::int16_t w7) {
  const unsigned b = base(axis);
  w.w[b + m::out_word::kMsw] = static_cast<std::int16_t>(msw);
  w.w[b + m::out_word::kLsw] = static_cast<std::int16_t>(lsw);
  put_split(w, b, m::out_word::kTargetMsw, w23);
  put_split(w, b, m::out_word::kSpeedMsw, w45);
  w.w[b + m::out_word::kAccel] = w6;
  w.w[b + m::out_word::kDecel] = w7;
}

void put_configuration(ImageWords& w, unsigned axis, std::uint16_t cfg_msw, std::uint16_t cfg_lsw,
                       std::int32_t start_speed, std::int16_t homing_timeout_s) {
  const unsigned b = base(axis);
  for (unsigned i = 0; i < m::kWordsPerAxis; ++i) w.w[b + i] = 0;
  w.w[b + m::out_word::kMsw] = static_cast<std::int16_t>(cfg_msw | m::cfg_msw::kConfigMode);
  w.w[b + m::out_word::kLsw] = static_cast<std::int16_t>(cfg_lsw);
  put_split(w, b, m::out_word::kStartingSpeedMsw, start_speed);
  w.w[b + m::out_word::kHomingTimeout] = homing_timeout_s;
}

std::uint16_t accel_bits(AccelType t) {
  switch (t) {
    case AccelType::kConstant:
      return 0;
    case AccelType::kTriangularS:
      return m::cmd_lsw::kSCurve;
    case AccelType::kTrapezoidalS:
      return m::cmd_lsw::kSCurve | m::cmd_lsw::kTrapezoidalS;
  }
  return 0;
}

}  // namespace stepmod::plc::m3602

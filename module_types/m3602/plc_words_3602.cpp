#include "module_types/m3602/plc_words_3602.hpp"

#include "module_types/m3602/words_3602.hpp"
#include "plc/accel_bits.hpp"

namespace stepmod::plc::m3602 {

namespace m = words::m3602;

unsigned base(unsigned axis) {
  return m::kWordsPerAxis * axis;
}

void put_split(ImageWords& w, unsigned b, unsigned index, std::int32_t value) {
  const auto p = words::encode_3602(value);
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
  return accel_bits_in<std::uint16_t>(m::kCommandLswBits, t);
}

void put_axis(ImageWords& w, unsigned axis, const AxisWords& a) {
  const unsigned b = base(axis);
  for (unsigned i = 0; i < a.size(); ++i) w.w[b + i] = a[i];
}

std::vector<AxisWords> blend_blocks(const BlendProfile& b) {
  constexpr std::uint16_t kFinalValue = 0x07FF;  // bits 13..11 must stay 0
  std::vector<AxisWords> blocks;
  AxisWords first{};
  first[2] = static_cast<std::int32_t>(b.segments.size());
  const TypePairs pairs = segment_type_pairs(b, accel_bits);  // as the 3601 (3602 manual ch. 9)
  first[3] = static_cast<std::int16_t>(pairs.hi);
  first[4] = static_cast<std::int16_t>(pairs.lo);
  first[5] =
      static_cast<std::int16_t>(accel_bits(b.final_type) << 14 | (b.final_decel & kFinalValue));
  blocks.push_back(first);
  for (const BlendSegment& s : b.segments) {
    AxisWords blk{};
    const auto length = words::encode_3602(s.length);
    const auto speed = words::encode_3602(s.speed);
    blk[m::out_word::kTargetMsw] = length.msw;
    blk[m::out_word::kTargetLsw] = length.lsw;
    blk[m::out_word::kSpeedMsw] = speed.msw;
    blk[m::out_word::kSpeedLsw] = speed.lsw;
    blk[m::out_word::kAccel] = static_cast<std::int16_t>(s.accel);
    blocks.push_back(blk);
  }
  return blocks;
}

}  // namespace stepmod::plc::m3602

#include "module_types/m3601/plc_words_3601.hpp"

#include "module_types/m3601/words_3601.hpp"
#include "plc/accel_bits.hpp"

namespace stepmod::plc::m3601 {

namespace m = words::m3601;

void put_split(ImageWords& w, unsigned msw_index, std::int64_t value) {
  const words::WordPair p = words::encode_3601(value);
  w.w[msw_index] = p.msw;
  w.w[msw_index + 1] = p.lsw;
}

void put_profile(ImageWords& w, const Profile& p) {
  put_split(w, m::out_word::kSpeedMsw, p.speed);
  w.w[m::out_word::kAccel] = p.accel;
  w.w[m::out_word::kDecel] = p.decel;
}

ImageWords command_words(std::uint16_t msw, std::uint16_t lsw, std::int32_t w23, std::int32_t w45,
                         std::int16_t w6, std::int16_t w7) {
  ImageWords w;
  w.w[m::out_word::kMsw] = static_cast<std::int16_t>(msw);
  w.w[m::out_word::kLsw] = static_cast<std::int16_t>(lsw);
  put_split(w, m::out_word::kTargetMsw, w23);
  put_split(w, m::out_word::kSpeedMsw, w45);
  w.w[m::out_word::kAccel] = w6;
  w.w[m::out_word::kDecel] = w7;
  return w;
}

ImageWords configuration_words(std::uint16_t cfg_msw, std::uint16_t cfg_lsw,
                               std::int32_t start_speed) {
  ImageWords w;
  w.w[m::out_word::kMsw] = static_cast<std::int16_t>(cfg_msw | m::cfg_msw::kConfigMode);
  w.w[m::out_word::kLsw] = static_cast<std::int16_t>(cfg_lsw);
  put_split(w, m::out_word::kTargetMsw, start_speed);  // starting speed
  return w;
}

ImageWords follower_words(std::uint16_t msw, std::int16_t multiplier, std::int16_t divisor,
                          std::int16_t accel, std::int16_t decel, std::uint16_t lsw) {
  ImageWords w;
  w.w[m::out_word::kMsw] = static_cast<std::int16_t>(msw);
  w.w[m::out_word::kLsw] = static_cast<std::int16_t>(lsw);
  w.w[m::out_word::kTargetMsw] = multiplier;
  w.w[m::out_word::kTargetLsw] = divisor;
  w.w[m::out_word::kAccel] = accel;
  w.w[m::out_word::kDecel] = decel;
  return w;
}

std::uint16_t accel_bits(AccelType t) {
  return accel_bits_in<std::uint16_t>(m::kCommandLswBits, t);
}

std::vector<ImageWords> blend_blocks(const BlendProfile& b) {
  std::vector<ImageWords> blocks;
  ImageWords first;
  first.w[2] = static_cast<std::int32_t>(b.segments.size());
  // Type pairs: two bits per segment, segments 1..8 in word 4, 9..16 in word 3 (low bit S-curve,
  // high bit trapezoidal: the command LSW's code, 3601 manual ch. 5).
  const TypePairs pairs = segment_type_pairs(b, accel_bits);
  first.w[3] = static_cast<std::int16_t>(pairs.hi);
  first.w[4] = static_cast<std::int16_t>(pairs.lo);
  // Word 5: type in bits 15..14, value in bits 13..0.
  first.w[5] = static_cast<std::int16_t>(accel_bits(b.final_type) << 14 | (b.final_decel & 0x3FFF));
  blocks.push_back(first);
  for (const BlendSegment& s : b.segments) {
    ImageWords blk;
    put_split(blk, 2, s.length);
    put_split(blk, 4, s.speed);
    blk.w[6] = s.accel;
    blocks.push_back(blk);
  }
  return blocks;
}

}  // namespace stepmod::plc::m3601

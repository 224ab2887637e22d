#include "module_types/m3202/plc_words_3202.hpp"

#include "module_types/m3202/words_3202.hpp"
#include "plc/accel_bits.hpp"

namespace stepmod::plc::m3202 {

namespace mw = words::m3202;

ChannelWords command_words(std::uint32_t command, std::int32_t target, std::int32_t speed,
                           std::int32_t accel, std::int32_t decel) {
  ChannelWords w{};
  w[mw::out_word::kCommand] = static_cast<std::int32_t>(command);
  w[mw::out_word::kTarget] = target;
  w[mw::out_word::kSpeed] = speed;
  w[mw::out_word::kAccel] = accel;
  w[mw::out_word::kDecel] = decel;
  return w;
}

ChannelWords configuration_words(std::uint32_t bits, std::int32_t start_speed) {
  ChannelWords w{};
  w[mw::out_word::kCommand] = static_cast<std::int32_t>(bits | mw::cfg_bit::kConfigMode);
  w[mw::out_word::kTarget] = start_speed;
  return w;
}

std::uint32_t accel_bits(AccelType t) {
  return accel_bits_in<std::uint32_t>(mw::kCommandBits, t);
}

std::array<std::int32_t, 52> blend_message(std::int32_t channel_number, const BlendProfile& b) {
  std::array<std::int32_t, 52> d{};
  d[0] = channel_number;
  d[1] = static_cast<std::int32_t>(b.segments.size());
  std::uint32_t pairs = 0;
  // The pair code: bit 0 S-curve, bit 1 trapezoidal (3202 manual ch. 5, same code as bits 16/17).
  auto pair = [](AccelType t) { return accel_bits(t) >> 16; };
  for (std::size_t n = 0; n < b.segments.size() && n < 16; ++n) {
    pairs |= pair(b.segments[n].type) << (2 * n);
    d[4 + 3 * n] = b.segments[n].length;
    d[5 + 3 * n] = b.segments[n].speed;
    d[6 + 3 * n] = b.segments[n].accel;
  }
  d[2] = static_cast<std::int32_t>(pairs);
  d[3] = static_cast<std::int32_t>((pair(b.final_type) << 30) |
                                   (static_cast<std::uint32_t>(b.final_decel) & 0x3FFF'FFFFu));
  return d;
}

}  // namespace stepmod::plc::m3202

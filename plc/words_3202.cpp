#include "plc/words_3202.hpp"

#include "module/m3202/words_3202.hpp"

namespace stepmod::plc::m3202 {

namespace mw = module::m3202;

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

}  // namespace stepmod::plc::m3202

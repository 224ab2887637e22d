#pragma once
// A 3202 channel's input DINTs decoded for a PLC program (3202 manual ch. 6): the status word and
// the native 32-bit registers. Bit constants: module_types/m3202/words_3202.hpp.
#include <cstdint>

#include "core/module_shape.hpp"
#include "module_types/m3202/words_3202.hpp"

namespace stepmod::plc::m3202 {

struct Status {
  std::uint32_t word = 0;     // status word (configuration mode: the configuration echo)
  std::int32_t position = 0;  // command mode (configuration mode: the starting speed echo)
  std::int32_t encoder = 0;
  std::int32_t capture = 0;  // configuration mode: the firmware revision

  bool has(std::uint32_t bit) const { return (word & bit) != 0; }
  // "Pulses being output" (Moving CW or CCW).
  bool moving() const {
    return has(words::m3202::status_bit::kMovingCw | words::m3202::status_bit::kMovingCcw);
  }
};

// `channel`: 0 (the manual's channel 1, DINTs 0..7) or 1 (channel 2, DINTs 8..15).
inline Status decode_status(const ImageWords& in, unsigned channel) {
  namespace iw = words::m3202::in_word;
  const unsigned b = words::m3202::channel_base(channel);
  Status s;
  s.word = static_cast<std::uint32_t>(in.w[b + iw::kStatus]);
  s.position = in.w[b + iw::kPosition];
  s.encoder = in.w[b + iw::kEncoder];
  s.capture = in.w[b + iw::kCapture];
  return s;
}

// The status word of `channel`, with the error bits (plc/driver.hpp).
inline std::uint32_t status_word(const ImageWords& in, unsigned channel) {
  return decode_status(in, channel).word;
}

}  // namespace stepmod::plc::m3202

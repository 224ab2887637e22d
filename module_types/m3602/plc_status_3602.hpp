#pragma once
// A 3602's input words decoded for a PLC program, per axis (3602 manual table 8.5, ch. 9): status
// bits and the binary-split registers. Bit constants: module_types/m3602/words_3602.hpp.
#include <cstdint>

#include "core/module_shape.hpp"
#include "module_types/m3602/words_3602.hpp"
#include "plc/status_words16.hpp"

namespace stepmod::plc::m3602 {

struct Status : StatusWords16<words::m3602::status_msw::kMovingCw |
                               words::m3602::status_msw::kMovingCcw> {
  std::int32_t position = 0;  // command mode only
  std::int32_t capture = 0;
};

// The status of `axis` (0 or 1) in the input image.
inline Status decode_status(const ImageWords& in, unsigned axis) {
  namespace iw = words::m3602::in_word;
  const unsigned b = words::m3602::kWordsPerAxis * axis;
  using words::decode_3602;
  Status s;
  s.msw = static_cast<std::uint16_t>(in.w[b + iw::kStatusMsw]);
  s.lsw = static_cast<std::uint16_t>(in.w[b + iw::kStatusLsw]);
  s.position = decode_3602(in.w[b + iw::kPositionMsw], in.w[b + iw::kPositionMsw + 1]);
  s.capture = decode_3602(in.w[b + iw::kCaptureMsw], in.w[b + iw::kCaptureMsw + 1]);
  return s;
}

// The status MSW of `axis`, the word with the error bits (plc/driver.hpp).
inline std::uint32_t status_msw(const ImageWords& in, unsigned axis) {
  return decode_status(in, axis).msw;
}

}  // namespace stepmod::plc::m3602

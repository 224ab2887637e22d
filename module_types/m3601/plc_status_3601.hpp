#pragma once
// A 3601's input words decoded for a PLC program (3601 manual ch. 6): status bits and the
// decimal-split registers. Bit constants: module_types/m3601/words_3601.hpp.
#include <cstdint>

#include "core/module_shape.hpp"
#include "module_types/m3601/words_3601.hpp"
#include "plc/status_words16.hpp"

namespace stepmod::plc::m3601 {

struct Status : StatusWords16<words::m3601::status_msw::kMovingCw |
                               words::m3601::status_msw::kMovingCcw> {
  std::int64_t position = 0;  // command mode only
  std::int64_t encoder = 0;
  std::int64_t capture = 0;
};

inline Status decode_status(const ImageWords& in) {
  namespace iw = words::m3601::in_word;
  using words::decode_3601_report;
  Status s;
  s.msw = static_cast<std::uint16_t>(in.w[iw::kStatusMsw]);
  s.lsw = static_cast<std::uint16_t>(in.w[iw::kStatusLsw]);
  s.position = decode_3601_report(in.w[iw::kPositionMsw], in.w[iw::kPositionLsw]);
  s.encoder = decode_3601_report(in.w[iw::kEncoderMsw], in.w[iw::kEncoderLsw]);
  s.capture = decode_3601_report(in.w[iw::kCaptureMsw], in.w[iw::kCaptureLsw]);
  return s;
}

// The status MSW, the word with the error bits (plc/driver.hpp); one axis.
inline std::uint32_t status_msw(const ImageWords& in, unsigned /*axis*/) {
  return static_cast<std::uint16_t>(in.w[words::m3601::in_word::kStatusMsw]);
}

}  // namespace stepmod::plc::m3601

// How stepmodctl shows a 3601's input image: the decoded status display (stepmodctl status) and
// the axis summary (--brief, --json, wait-idle, --wait). Names from the 3601's bit tables,
// numbers in its decimal split (module_types/m3601/words_3601.hpp). Both are in its stepmodctl row.
#include <sstream>
#include <string>
#include <vector>

#include "module_types/m3601/ctl_3601.hpp"
#include "module_types/m3601/plc_status_3601.hpp"
#include "module_types/m3601/words_3601.hpp"
#include "tools/ctl_fields.hpp"
#include "tools/ctl_status.hpp"
#include "tools/ctl_summary.hpp"

namespace stepmod::tools::ctl {

template <>
void CtlOf<ModuleType::k3601>::format_status(std::ostringstream& o, const ImageWords& in) {
  namespace m = words::m3601;
  const std::uint16_t w0 = u16(in.w[m::in_word::kStatusMsw]);
  const std::uint16_t w1 = u16(in.w[m::in_word::kStatusLsw]);
  if (w0 & m::status_msw::kConfigMode) {
    o << "3601 in CONFIGURATION mode\n";
    o << "  configuration bits MSW (mirror) = 16#" << hex(w0, 4) << "\n";
    // Bits 0..12 mirror the configuration; 13 and 14 are status (3601 manual ch. 3).
    for (const NamedBit& b : m::kConfigMswBits) {
      if ((1u << b.bit) < m::status_msw::kConfigurationError) one_field(o, w0, b);
    }
    for (const NamedBit& b : m::kStatusMswBits) {
      const auto mask = 1u << b.bit;
      if (mask == m::status_msw::kConfigurationError || mask == m::status_msw::kModuleOk) {
        one_field(o, w0, b);
      }
    }
    o << "  input active levels LSW (mirror) = 16#" << hex(w1, 4) << "\n";
    const auto vs = words::decode_3601_unsigned(in.w[m::in_word::kStartingSpeedMsw],
                                                in.w[m::in_word::kStartingSpeedLsw]);
    o << "  starting speed = "
      << (vs ? std::to_string(*vs)
             : std::string("(invalid words ") +
                   std::to_string(in.w[m::in_word::kStartingSpeedMsw]) + ", " +
                   std::to_string(in.w[m::in_word::kStartingSpeedLsw]) + ")")
      << " steps/s\n";
    o << "  firmware = " << in.w[m::in_word::kFirmwareMajor] << "."
      << in.w[m::in_word::kFirmwareMinor] << "\n";
    return;
  }
  o << "3601 in COMMAND mode\n";
  o << "  status MSW = 16#" << hex(w0, 4) << "  [" << set_bit_names(w0, m::kStatusMswBits) << "]\n";
  all_bits(o, w0, m::kStatusMswBits);
  o << "  status LSW = 16#" << hex(w1, 4) << "  [" << set_bit_names(w1, m::kStatusLswBits) << "]\n";
  all_bits(o, w1, m::kStatusLswBits);
  using words::decode_3601_report;
  namespace iw = m::in_word;
  o << "  position = " << decode_3601_report(in.w[iw::kPositionMsw], in.w[iw::kPositionLsw])
    << "\n";
  o << "  encoder  = " << decode_3601_report(in.w[iw::kEncoderMsw], in.w[iw::kEncoderLsw]) << "\n";
  o << "  capture  = " << decode_3601_report(in.w[iw::kCaptureMsw], in.w[iw::kCaptureLsw]) << "\n";
}

template <>
std::vector<AxisSummary> CtlOf<ModuleType::k3601>::summarize(const ImageWords& in) {
  constexpr auto kBits = summary_bits_of(words::m3601::kStatusMswBits);
  const plc::m3601::Status st = plc::m3601::decode_status(in);
  AxisSummary s = summary_from_word(st.msw, kBits);
  s.blend_running = st.has_lsw(words::m3601::status_lsw::kBlendRunning);
  s.position = st.position;
  return {s};
}

}  // namespace stepmod::tools::ctl

// How stepmodctl shows a 3202's input image: the decoded status display of both channels
// (stepmodctl status) and the channel summaries (--brief, --json, wait-idle, --wait). Names from
// the 3202's bit tables (module_types/m3202/words_3202.hpp). Both are in its stepmodctl row.
#include <sstream>
#include <string>
#include <vector>

#include "module_types/m3202/ctl_3202.hpp"
#include "module_types/m3202/plc_status_3202.hpp"
#include "module_types/m3202/words_3202.hpp"
#include "tools/ctl_fields.hpp"
#include "tools/ctl_status.hpp"
#include "tools/ctl_summary.hpp"

namespace stepmod::tools::ctl {

template <>
void CtlOf<ModuleType::k3202>::format_status(std::ostringstream& o, const ImageWords& in) {
  namespace m = words::m3202;
  constexpr unsigned kStatus = index_of(m::kInputWords, "Status Word");
  constexpr unsigned kPosition = index_of(m::kInputWords, "Position");
  constexpr unsigned kEncoder = index_of(m::kInputWords, "Encoder");
  constexpr unsigned kCapture = index_of(m::kInputWords, "Capture");
  constexpr unsigned kSpeed = index_of(m::kInputWords, "Starting Speed");
  constexpr unsigned kFirmware = index_of(m::kInputWords, "Firmware Revision");
  constexpr auto kConfigMode = mask_of<std::uint32_t>(m::kStatusBits, "Configuration Mode");
  constexpr auto kCfgError = mask_of<std::uint32_t>(m::kConfigEchoBits, "Configuration Error");
  constexpr auto kDisabled = mask_of<std::uint32_t>(m::kConfigEchoBits, "Channel Disabled");
  constexpr auto kModuleOk = mask_of<std::uint32_t>(m::kConfigEchoBits, "Module OK");
  for (unsigned ch = 0; ch < 2; ++ch) {
    const unsigned b = m::kWordsPerChannel * ch;
    const auto w0 = static_cast<std::uint32_t>(in.w[b + kStatus]);
    o << "3202 channel " << ch + 1;
    if (w0 & kConfigMode) {
      o << " in CONFIGURATION mode\n";
      o << "  configuration bits (mirror) = 16#" << hex(w0, 8)
        << "  Configuration Error=" << ((w0 & kCfgError) != 0)
        << "  disabled=" << ((w0 & kDisabled) != 0) << "  Module OK=" << ((w0 & kModuleOk) != 0)
        << "\n";
      o << "  starting speed = " << in.w[b + kSpeed] << " steps/s\n";
      // Firmware: major revision in bits 31..16, minor in 15..0 (3202 manual ch. 3).
      const auto fw = static_cast<std::uint32_t>(in.w[b + kFirmware]);
      o << "  firmware = " << (fw >> 16) << "." << (fw & 0xFFFF) << "\n";
      continue;
    }
    o << " in COMMAND mode\n";
    o << "  status = 16#" << hex(w0, 8) << "  [" << set_bit_names(w0, m::kStatusBits) << "]\n";
    all_bits(o, w0, m::kStatusBits);
    o << "  position = " << in.w[b + kPosition] << "\n";
    o << "  encoder  = " << in.w[b + kEncoder] << "\n";
    o << "  capture  = " << in.w[b + kCapture] << "\n";
  }
}

template <>
std::vector<AxisSummary> CtlOf<ModuleType::k3202>::summarize(const ImageWords& in) {
  constexpr auto kBits = summary_bits_of(words::m3202::kStatusBits);
  std::vector<AxisSummary> out;
  for (unsigned c = 0; c < 2; ++c) {
    const plc::m3202::Status st = plc::m3202::decode_status(in, c);
    AxisSummary s = summary_from_word(st.word, kBits);
    s.position = st.position;
    out.push_back(s);
  }
  return out;
}

}  // namespace stepmod::tools::ctl

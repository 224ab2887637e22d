// How stepmodctl shows a 3602's input image: the decoded status display of both axes (stepmodctl
// status) and the axis summaries (--brief, --json, wait-idle, --wait). Names from the 3602's bit
// tables, numbers in its binary split (module_types/m3602/words_3602.hpp). Both are columns of its
// registry row.
#include <sstream>
#include <string>
#include <vector>

#include "module_types/m3602/ctl_3602.hpp"
#include "module_types/m3602/plc_status_3602.hpp"
#include "module_types/m3602/words_3602.hpp"
#include "tools/ctl_fields.hpp"
#include "tools/ctl_status.hpp"
#include "tools/ctl_summary.hpp"

namespace stepmod::tools::ctl {

template <>
void CtlOf<ModuleType::k3602>::format_status(std::ostringstream& o, const ImageWords& in) {
  namespace m = words::m3602;
  namespace iw = m::in_word;
  namespace sm = m::status_msw;
  for (unsigned ax = 0; ax < 2; ++ax) {
    const unsigned b = m::kWordsPerAxis * ax;
    const std::uint16_t w0 = u16(in.w[b + iw::kStatusMsw]);
    const std::uint16_t w1 = u16(in.w[b + iw::kStatusLsw]);
    o << "3602 axis " << ax + 1;
    if (w0 & sm::kConfigMode) {
      o << " in CONFIGURATION mode\n";
      o << "  configuration bits MSW (echo) = 16#" << hex(w0, 4)
        << "  Configuration Error=" << ((w0 & sm::kConfigurationError) != 0)
        << "  axis enabled=" << ((w0 & sm::kAxisEnabled) != 0) << "\n";
      o << "  configuration bits LSW (echo) = 16#" << hex(w1, 4) << "\n";
      o << "  starting speed = "
        << words::decode_3602(in.w[b + iw::kStartingSpeedMsw], in.w[b + iw::kStartingSpeedMsw + 1])
        << " steps/s\n";
      o << "  homing timeout = " << in.w[b + iw::kHomingTimeout] << " s\n";
      continue;
    }
    o << " in COMMAND mode\n";
    o << "  status MSW = 16#" << hex(w0, 4) << "  [" << set_bit_names(w0, m::kStatusMswBits)
      << "]\n";
    all_bits(o, w0, m::kStatusMswBits);
    o << "  status LSW = 16#" << hex(w1, 4) << "  [" << set_bit_names(w1, m::kStatusLswBits)
      << "]\n";
    all_bits(o, w1, m::kStatusLswBits);
    o << "  position = "
      << words::decode_3602(in.w[b + iw::kPositionMsw], in.w[b + iw::kPositionMsw + 1]) << "\n";
    o << "  capture  = "
      << words::decode_3602(in.w[b + iw::kCaptureMsw], in.w[b + iw::kCaptureMsw + 1]) << "\n";
  }
}

template <>
std::vector<AxisSummary> CtlOf<ModuleType::k3602>::summarize(const ImageWords& in) {
  constexpr auto kBits = summary_bits_of(words::m3602::kStatusMswBits);
  std::vector<AxisSummary> out;
  for (unsigned a = 0; a < 2; ++a) {
    const plc::m3602::Status st = plc::m3602::decode_status(in, a);
    AxisSummary s = summary_from_word(st.msw, kBits);
    s.blend_running = st.has_lsw(words::m3602::status_lsw::kBlendRunning);
    s.position = st.position;
    out.push_back(s);
  }
  return out;
}

}  // namespace stepmod::tools::ctl

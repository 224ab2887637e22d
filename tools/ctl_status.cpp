#include "tools/ctl_status.hpp"

#include <cstdio>
#include <sstream>

#include "ipc/codec.hpp"
#include "module/m3202/words_3202.hpp"
#include "module/m3601/words_3601.hpp"
#include "module/m3602/words_3602.hpp"
#include "tools/ctl_args.hpp"

namespace stepmod::tools::ctl {
namespace {

std::uint16_t u16(std::int32_t w) {
  return static_cast<std::uint16_t>(w & 0xFFFF);
}

std::string hex(std::uint32_t v, unsigned digits) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%0*X", static_cast<int>(digits), v);
  return buf;
}

// One field with its state: "    1  bit 12  Command Error".
void one_field(std::ostringstream& o, std::uint32_t word, const NamedBit& b) {
  o << "    " << plc::field_value(word, b) << "  bit " << (b.bit < 10 ? " " : "") << b.bit << "  "
    << b.name << "\n";
}

// Every named field with its state, so that "not set" is visible too (a person debugging a PLC
// program wants to see the zero as much as the one).
void all_bits(std::ostringstream& o, std::uint32_t word, BitTable table) {
  for (const NamedBit& b : table) one_field(o, word, b);
}

void format_3601(std::ostringstream& o, const ImageWords& in) {
  namespace m = module::m3601;
  const std::uint16_t w0 = u16(in.w[m::in_word::kStatusMsw]);
  const std::uint16_t w1 = u16(in.w[m::in_word::kStatusLsw]);
  if (w0 & m::status_msw::kConfigMode) {
    o << "3601 in CONFIGURATION mode\n";
    o << "  configuration bits MSW (mirror) = 16#" << hex(w0, 4) << "\n";
    // Bits 0..12 mirror the configuration; 13 and 14 are status (digest 3.4).
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
    const auto vs = ipc::codec::decode_3601_unsigned(in.w[m::in_word::kStartingSpeedMsw],
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
  using ipc::codec::decode_3601_report;
  namespace iw = m::in_word;
  o << "  position = " << decode_3601_report(in.w[iw::kPositionMsw], in.w[iw::kPositionLsw])
    << "\n";
  o << "  encoder  = " << decode_3601_report(in.w[iw::kEncoderMsw], in.w[iw::kEncoderLsw]) << "\n";
  o << "  capture  = " << decode_3601_report(in.w[iw::kCaptureMsw], in.w[iw::kCaptureLsw]) << "\n";
}

void format_3602(std::ostringstream& o, const ImageWords& in) {
  namespace m = module::m3602;
  constexpr unsigned kMsw = index_of(m::kInputWords, "Status Bits MSW");
  constexpr unsigned kLsw = index_of(m::kInputWords, "Status Bits LSW");
  constexpr unsigned kPosition = index_of(m::kInputWords, "Position MSW");
  constexpr unsigned kCapture = index_of(m::kInputWords, "Capture MSW");
  constexpr unsigned kSpeed = index_of(m::kInputWords, "Starting Speed MSW");
  constexpr unsigned kTimeout = index_of(m::kInputWords, "Homing Timeout");
  constexpr auto kConfigMode = mask_of<std::uint16_t>(m::kStatusMswBits, "Configuration Mode");
  constexpr auto kCfgError = mask_of<std::uint16_t>(m::kStatusMswBits, "Configuration Error");
  constexpr auto kEnabled = mask_of<std::uint16_t>(m::kStatusMswBits, "Axis Enabled");
  for (unsigned ax = 0; ax < 2; ++ax) {
    const unsigned b = m::kWordsPerAxis * ax;
    const std::uint16_t w0 = u16(in.w[b + kMsw]);
    const std::uint16_t w1 = u16(in.w[b + kLsw]);
    o << "3602 axis " << ax + 1;
    if (w0 & kConfigMode) {
      o << " in CONFIGURATION mode\n";
      o << "  configuration bits MSW (echo) = 16#" << hex(w0, 4)
        << "  Configuration Error=" << ((w0 & kCfgError) != 0)
        << "  axis enabled=" << ((w0 & kEnabled) != 0) << "\n";
      o << "  configuration bits LSW (echo) = 16#" << hex(w1, 4) << "\n";
      o << "  starting speed = " << ipc::codec::decode_3602(in.w[b + kSpeed], in.w[b + kSpeed + 1])
        << " steps/s\n";
      o << "  homing timeout = " << in.w[b + kTimeout] << " s\n";
      continue;
    }
    o << " in COMMAND mode\n";
    o << "  status MSW = 16#" << hex(w0, 4) << "  [" << set_bit_names(w0, m::kStatusMswBits)
      << "]\n";
    all_bits(o, w0, m::kStatusMswBits);
    o << "  status LSW = 16#" << hex(w1, 4) << "  [" << set_bit_names(w1, m::kStatusLswBits)
      << "]\n";
    all_bits(o, w1, m::kStatusLswBits);
    o << "  position = " << ipc::codec::decode_3602(in.w[b + kPosition], in.w[b + kPosition + 1])
      << "\n";
    o << "  capture  = " << ipc::codec::decode_3602(in.w[b + kCapture], in.w[b + kCapture + 1])
      << "\n";
  }
}

void format_3202(std::ostringstream& o, const ImageWords& in) {
  namespace m = module::m3202;
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
      // Firmware: major revision in bits 31..16, minor in 15..0 (digest 5.3).
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

}  // namespace

std::string format_status(ModuleType type, const ImageWords& in) {
  std::ostringstream o;
  switch (type) {
    case ModuleType::k3601:
      format_3601(o, in);
      break;
    case ModuleType::k3602:
      format_3602(o, in);
      break;
    case ModuleType::k3202:
      format_3202(o, in);
      break;
  }
  return o.str();
}

std::string format_health(const ipc::Health& h) {
  std::ostringstream o;
  o << "daemon health = 16#" << hex(h.flags, 4) << "  [" << ipc::health_flag_names(h.flags)
    << "]\n";
  o << "  late-edge faults = " << h.late_faults;
  if (h.late_faults > 0) o << ", worst " << h.worst_late_us << " us late";
  o << "\n";
  return o.str();
}

std::string format_panel(const ipc::SimPanelClient& p) {
  std::string s;
  for (unsigned a = 0; a < p.axes(); ++a) {
    const ipc::PanelAxis x = p.read(a);
    s += "axis " + std::to_string(a + 1) + ": position " + std::to_string(x.position) +
         "  encoder " + std::to_string(x.encoder) +
         "  outputs step/cw=" + std::to_string(x.outputs & 1) +
         " dir/ccw=" + std::to_string((x.outputs >> 1) & 1) +
         " gpo=" + std::to_string((x.outputs >> 2) & 1) + "\n  forced:";
    bool any = false;
    for (unsigned i = 0; i < 6; ++i) {
      if (x.force_mask & (1u << i)) {
        s += std::string(" ") + kInputNames[i] + "=" + std::to_string((x.force_levels >> i) & 1);
        any = true;
      }
    }
    s += any ? "\n" : " none\n";
  }
  return s;
}

std::string format_words(const ImageWords& w, unsigned count, unsigned word_bytes) {
  std::ostringstream o;
  for (unsigned i = 0; i < count; ++i) {
    const std::uint32_t raw = word_bytes == 2 ? (static_cast<std::uint32_t>(w.w[i]) & 0xFFFFu)
                                              : static_cast<std::uint32_t>(w.w[i]);
    char buf[64];
    std::snprintf(buf, sizeof buf, "  [%2u] %11d  16#%s\n", i, w.w[i],
                  hex(raw, word_bytes * 2).c_str());
    o << buf;
  }
  return o.str();
}

}  // namespace stepmod::tools::ctl

#include "tools/ctl_status.hpp"

#include <cstdio>
#include <sstream>

#include "ipc/codec.hpp"
#include "module/m3601/words_3601.hpp"

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

// Every named bit with its state, so that "not set" is visible too (a person debugging a PLC
// program wants to see the zero as much as the one).
void all_bits(std::ostringstream& o, std::uint32_t word, const std::vector<BitName>& names) {
  for (const BitName& b : names) {
    o << "    " << ((word >> b.bit) & 1u) << "  bit " << (b.bit < 10 ? " " : "") << b.bit << "  "
      << b.name << "\n";
  }
}

void format_3601(std::ostringstream& o, const ImageWords& in) {
  namespace m = module::m3601;
  const std::uint16_t w0 = u16(in.w[m::in_word::kStatusMsw]);
  const std::uint16_t w1 = u16(in.w[m::in_word::kStatusLsw]);
  if (w0 & m::status_msw::kConfigMode) {
    o << "3601 in CONFIGURATION mode\n";
    o << "  configuration bits MSW (mirror) = 16#" << hex(w0, 4) << "\n";
    all_bits(o, w0 & 0x1FFF, config_msw_names_3601());
    o << "    " << ((w0 >> 13) & 1u) << "  bit 13  Configuration Error\n";
    o << "    " << ((w0 >> 14) & 1u) << "  bit 14  Module OK\n";
    o << "  input active levels LSW (mirror) = 16#" << hex(w1, 4) << "\n";
    const auto vs = ipc::codec::decode_3601_unsigned(in.w[2], in.w[3]);
    o << "  starting speed = "
      << (vs ? std::to_string(*vs)
             : std::string("(invalid words ") + std::to_string(in.w[2]) + ", " +
                   std::to_string(in.w[3]) + ")")
      << " steps/s\n";
    o << "  firmware = " << in.w[m::in_word::kFirmwareMajor] << "."
      << in.w[m::in_word::kFirmwareMinor] << "\n";
    return;
  }
  o << "3601 in COMMAND mode\n";
  o << "  status MSW = 16#" << hex(w0, 4) << "  [" << set_bit_names(w0, status_msw_names_3601())
    << "]\n";
  all_bits(o, w0, status_msw_names_3601());
  o << "  status LSW = 16#" << hex(w1, 4) << "  [" << set_bit_names(w1, status_lsw_names_3601())
    << "]\n";
  all_bits(o, w1, status_lsw_names_3601());
  using ipc::codec::decode_3601_report;
  o << "  position = " << decode_3601_report(in.w[2], in.w[3]) << "\n";
  o << "  encoder  = " << decode_3601_report(in.w[4], in.w[5]) << "\n";
  o << "  capture  = " << decode_3601_report(in.w[6], in.w[7]) << "\n";
}

void format_3602(std::ostringstream& o, const ImageWords& in) {
  for (unsigned ax = 0; ax < 2; ++ax) {
    const unsigned b = 8 * ax;
    const std::uint16_t w0 = u16(in.w[b]);
    const std::uint16_t w1 = u16(in.w[b + 1]);
    o << "3602 axis " << ax + 1;
    if (w0 & 0x8000) {
      o << " in CONFIGURATION mode\n";
      o << "  configuration bits MSW (echo) = 16#" << hex(w0, 4)
        << "  Configuration Error=" << ((w0 >> 13) & 1) << "  axis enabled=" << ((w0 >> 14) & 1)
        << "\n";
      o << "  configuration bits LSW (echo) = 16#" << hex(w1, 4) << "\n";
      o << "  starting speed = " << ipc::codec::decode_3602(in.w[b + 2], in.w[b + 3])
        << " steps/s\n";
      o << "  homing timeout = " << in.w[b + 4] << " s\n";
      continue;
    }
    o << " in COMMAND mode\n";
    o << "  status MSW = 16#" << hex(w0, 4) << "  [" << set_bit_names(w0, status_msw_names_3602())
      << "]\n";
    all_bits(o, w0, status_msw_names_3602());
    o << "  status LSW = 16#" << hex(w1, 4) << "  [" << set_bit_names(w1, status_lsw_names_3602())
      << "]\n";
    all_bits(o, w1, status_lsw_names_3602());
    o << "  position = " << ipc::codec::decode_3602(in.w[b + 2], in.w[b + 3]) << "\n";
    o << "  capture  = " << ipc::codec::decode_3602(in.w[b + 6], in.w[b + 7]) << "\n";
  }
}

void format_3202(std::ostringstream& o, const ImageWords& in) {
  for (unsigned ch = 0; ch < 2; ++ch) {
    const unsigned b = 8 * ch;
    const auto w0 = static_cast<std::uint32_t>(in.w[b]);
    o << "3202 channel " << ch + 1;
    if (w0 & 0x80000000u) {
      o << " in CONFIGURATION mode\n";
      o << "  configuration bits (mirror) = 16#" << hex(w0, 8)
        << "  Configuration Error=" << ((w0 >> 13) & 1) << "  disabled=" << ((w0 >> 28) & 1)
        << "  Module OK=" << ((w0 >> 30) & 1) << "\n";
      o << "  starting speed = " << in.w[b + 1] << " steps/s\n";
      const auto fw = static_cast<std::uint32_t>(in.w[b + 3]);
      o << "  firmware = " << (fw >> 16) << "." << (fw & 0xFFFF) << "\n";
      continue;
    }
    o << " in COMMAND mode\n";
    o << "  status = 16#" << hex(w0, 8) << "  [" << set_bit_names(w0, status_names_3202()) << "]\n";
    all_bits(o, w0, status_names_3202());
    o << "  position = " << in.w[b + 1] << "\n";
    o << "  encoder  = " << in.w[b + 2] << "\n";
    o << "  capture  = " << in.w[b + 3] << "\n";
  }
}

}  // namespace

const std::vector<BitName>& status_msw_names_3601() {
  static const std::vector<BitName> v = {{0, "Moving CW"},         {1, "Moving CCW"},
                                         {2, "Hold State"},        {3, "Stopped"},
                                         {4, "At Home"},           {5, "Accelerating"},
                                         {6, "Decelerating"},      {7, "Move Complete"},
                                         {8, "Home Invalid"},      {9, "Invalid Profile"},
                                         {10, "Position Invalid"}, {11, "Input Error"},
                                         {12, "Command Error"},    {13, "Configuration Error"},
                                         {14, "Module OK"},        {15, "Configuration Mode"}};
  return v;
}

const std::vector<BitName>& status_lsw_names_3601() {
  static const std::vector<BitName> v = {{0, "Capture Input Active"},
                                         {1, "External Input Active"},
                                         {2, "Home Input Active"},
                                         {3, "E-Stop Input Active"},
                                         {4, "CW Limit Active"},
                                         {5, "CCW Limit Active"},
                                         {7, "Encoder Follower Mode"},
                                         {8, "Blend Move Running"},
                                         {9, "Blend Block Acknowledge"},
                                         {10, "Min. Registration Distance Set"},
                                         {12, "Backplane Home Proximity Echo"}};
  return v;
}

const std::vector<BitName>& config_msw_names_3601() {
  static const std::vector<BitName> v = {{0, "Capture Input Used"},
                                         {1, "External Input Used"},
                                         {2, "Home Input Used"},
                                         {3, "E-Stop Input Used"},
                                         {4, "CW Limit Used"},
                                         {5, "CCW Limit Used"},
                                         {6, "Backplane Home Proximity"},
                                         {8, "Quadrature Encoder"},
                                         {9, "Diagnostic Feedback"},
                                         {10, "Step+Direction Output (0 = CW/CCW)"},
                                         {12, "Marker Homing (0 = home switch)"}};
  return v;
}

const std::vector<BitName>& status_msw_names_3602() {
  static const std::vector<BitName> v = {{0, "CW Motion"},         {1, "CCW Motion"},
                                         {2, "Hold State"},        {3, "Axis Stopped"},
                                         {4, "At Home"},           {5, "Accelerating"},
                                         {6, "Decelerating"},      {7, "Move Complete"},
                                         {8, "Home Invalid"},      {9, "Invalid Profile"},
                                         {10, "Position Invalid"}, {11, "Input Error"},
                                         {12, "Command Error"},    {13, "Configuration Error"},
                                         {14, "Axis Enabled"},     {15, "Configuration Mode"}};
  return v;
}

const std::vector<BitName>& status_lsw_names_3602() {
  static const std::vector<BitName> v = {
      {0, "Capture Input Active"},       {1, "External Input Active"},
      {2, "Home Input Active"},          {3, "CW Input Active"},
      {4, "CCW Input Active"},           {8, "Blend Move Running"},
      {9, "Blend Block Acknowledge"},    {10, "Min. Registration Distance Set"},
      {11, "Interpolated Move Running"}, {12, "Backplane Home Proximity Echo"},
      {13, "General-Purpose Output"}};
  return v;
}

const std::vector<BitName>& status_names_3202() {
  static const std::vector<BitName> v = {{0, "Moving CW"},
                                         {1, "Moving CCW"},
                                         {2, "Hold State"},
                                         {3, "Stopped"},
                                         {4, "At Home"},
                                         {5, "Accelerating"},
                                         {6, "Decelerating"},
                                         {7, "Move Complete"},
                                         {8, "Blend Move Running"},
                                         {10, "Position Invalid"},
                                         {11, "Input Error"},
                                         {12, "Command Error"},
                                         {13, "Configuration Error"},
                                         {14, "Home Invalid"},
                                         {15, "Invalid Profile"},
                                         {16, "Capture Input Active"},
                                         {17, "External Input Active"},
                                         {18, "Home Input Active"},
                                         {19, "E-Stop Input Active"},
                                         {20, "CW Limit Active"},
                                         {21, "CCW Limit Active"},
                                         {28, "Channel Disabled"},
                                         {29, "Backplane Home Proximity Echo"},
                                         {30, "Module OK"},
                                         {31, "Configuration Mode"}};
  return v;
}

std::string set_bit_names(std::uint32_t word, const std::vector<BitName>& names) {
  std::string s;
  for (const BitName& b : names) {
    if ((word >> b.bit) & 1u) s += (s.empty() ? "" : ", ") + std::string(b.name);
  }
  return s.empty() ? "-" : s;
}

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

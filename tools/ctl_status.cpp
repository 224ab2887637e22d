#include "tools/ctl_status.hpp"

#include <cstdio>
#include <sstream>

#include "tools/ctl_args.hpp"
#include "tools/ctl_dialects.hpp"
#include "tools/ctl_fields.hpp"

namespace stepmod::tools::ctl {

std::uint16_t u16(std::int32_t w) {
  return static_cast<std::uint16_t>(w & 0xFFFF);
}

std::string hex(std::uint32_t v, unsigned digits) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%0*X", static_cast<int>(digits), v);
  return buf;
}

void one_field(std::ostringstream& o, std::uint32_t word, const NamedBit& b) {
  o << "    " << plc::field_value(word, b) << "  bit " << (b.bit < 10 ? " " : "") << b.bit << "  "
    << b.name << "\n";
}

void all_bits(std::ostringstream& o, std::uint32_t word, BitTable table) {
  for (const NamedBit& b : table) one_field(o, word, b);
}

std::string format_status(ModuleType type, const ImageWords& in) {
  std::ostringstream o;
  ctl_row_of(type).format_status(o, in);
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

#include "plc/bit_names.hpp"

namespace stepmod::plc {

std::string set_bit_names(std::uint32_t word, BitTable table) {
  std::string s;
  for (const NamedBit& b : table) {
    const std::uint32_t v = field_value(word, b);
    if (v == 0) continue;
    // Appended piece by piece: `"x" + std::string(...)` trips GCC 12's -O3 -Wrestrict false
    // positive (Release builds with STEPMOD_WERROR).
    if (!s.empty()) s += ", ";
    s += b.name;
    if (b.width > 1) {
      s += '=';
      s += std::to_string(v);
    }
  }
  return s.empty() ? "-" : s;
}

}  // namespace stepmod::plc

#pragma once
// Test helpers: packets written as hex text, as a capture shows them.
#include <cstdint>
#include <string_view>
#include <vector>

namespace stepmod::enip::test {

// "63 00 0a" -> {0x63, 0x00, 0x0a}; spaces and newlines are ignored.
inline std::vector<std::uint8_t> hex(std::string_view text) {
  std::vector<std::uint8_t> out;
  int high = -1;
  for (const char c : text) {
    int v = -1;
    if (c >= '0' && c <= '9') v = c - '0';
    if (c >= 'a' && c <= 'f') v = c - 'a' + 10;
    if (c >= 'A' && c <= 'F') v = c - 'A' + 10;
    if (v < 0) continue;
    if (high < 0) {
      high = v;
    } else {
      out.push_back(static_cast<std::uint8_t>(high * 16 + v));
      high = -1;
    }
  }
  return out;
}

inline std::vector<std::uint8_t> cat(std::vector<std::uint8_t> a,
                                     const std::vector<std::uint8_t>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

}  // namespace stepmod::enip::test

#pragma once
// The assembly instances (class 0x04) the adapter serves and their sizes, from the image's
// header: the module's words as its manual defines them (docs/ethernetip-design.md, "Assembly").
#include <cstdint>

namespace stepmod::enip {

inline constexpr std::uint32_t kAssemblyClass = 0x04;
inline constexpr std::uint32_t kInputInstance = 100;        // T→O: the module's input words
inline constexpr std::uint32_t kOutputInstance = 150;       // O→T: the module's output words
inline constexpr std::uint32_t kConfigInstance = 151;       // configuration, size 0
inline constexpr std::uint32_t kInputOnlyHeartbeat = 198;   // O→T of an input-only connection
inline constexpr std::uint32_t kListenOnlyHeartbeat = 199;  // O→T of a listen-only connection

struct AssemblyLayout {
  std::uint16_t input_bytes = 0;   // instance 100
  std::uint16_t output_bytes = 0;  // instance 150
};

// From the image header's word size (2 or 4) and word counts (at most 16 each).
constexpr AssemblyLayout assembly_layout(unsigned word_bytes, unsigned output_words,
                                         unsigned input_words) noexcept {
  return {static_cast<std::uint16_t>(word_bytes * input_words),
          static_cast<std::uint16_t>(word_bytes * output_words)};
}

}  // namespace stepmod::enip

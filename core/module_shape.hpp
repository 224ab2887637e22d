#pragma once
// The module types stepmod emulates and the shape of each one's I/O image (INTERFACE.md section 3
// header fields): stated here once, read by the daemon, the PLC-side client, the config checker
// and the module layer.
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace stepmod {

enum class ModuleType : std::uint32_t { k3601 = 3601, k3602 = 3602, k3202 = 3202 };
inline constexpr std::array<ModuleType, 3> kModuleTypes = {ModuleType::k3601, ModuleType::k3602,
                                                           ModuleType::k3202};

// The backplane words of one image, sign-extended to 32 bits (16-bit modules use the low 16 bits
// of each value; ipc/ truncates and sign-extends at the shared-memory boundary).
struct ImageWords {
  std::array<std::int32_t, 16> w{};
  bool operator==(const ImageWords&) const = default;
};

// Static facts of a module type.
struct ModuleShape {
  ModuleType type;
  unsigned axes;          // axes (3601, 3602) or channels (3202)
  unsigned word_bytes;    // 2 or 4
  unsigned output_words;  // PLC -> module
  unsigned input_words;   // module -> PLC
};

constexpr ModuleShape shape_of(ModuleType t) noexcept {
  switch (t) {
    case ModuleType::k3601:
      return {t, 1, 2, 8, 8};
    case ModuleType::k3602:
      return {t, 2, 2, 16, 16};
    case ModuleType::k3202:
      return {t, 2, 4, 16, 16};
  }
  return {t, 0, 0, 0, 0};
}

// The type number as the image header and the config file carry it (3601, 3602, 3202).
constexpr std::optional<ModuleType> module_type_from_number(std::uint32_t n) noexcept {
  for (ModuleType t : kModuleTypes) {
    if (static_cast<std::uint32_t>(t) == n) return t;
  }
  return std::nullopt;
}
constexpr std::optional<ModuleType> module_type_from_name(std::string_view s) noexcept {
  if (s == "3601") return ModuleType::k3601;
  if (s == "3602") return ModuleType::k3602;
  if (s == "3202") return ModuleType::k3202;
  return std::nullopt;
}

}  // namespace stepmod

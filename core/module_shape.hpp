#pragma once
// The module types stepmod emulates and the shape of each one's I/O image (INTERFACE.md section 3
// header fields): stated here once, read by the daemon, the PLC-side client, the config checker
// and the module layer.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace stepmod {

// A module type is its number (3601, 3602, 3202), as the image header and the config file carry it.
enum class ModuleType : std::uint32_t { k3601 = 3601, k3602 = 3602, k3202 = 3202 };

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

// The image shape of every module type: the ground columns of its registry row
// (registry/module_registry.cpp), here because ipc/, plc/ and the config checker need them and
// sit below the registry. The one place a module's shape is written down.
inline constexpr std::array<ModuleShape, 3> kModuleShapes = {{
    {ModuleType::k3601, 1, 2, 8, 8},
    {ModuleType::k3602, 2, 2, 16, 16},
    {ModuleType::k3202, 2, 4, 16, 16},
}};

inline constexpr std::array<ModuleType, kModuleShapes.size()> kModuleTypes = [] {
  std::array<ModuleType, kModuleShapes.size()> types{};
  for (std::size_t i = 0; i < types.size(); ++i) types[i] = kModuleShapes[i].type;
  return types;
}();

constexpr ModuleShape shape_of(ModuleType t) noexcept {
  for (const ModuleShape& s : kModuleShapes) {
    if (s.type == t) return s;
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
// The name of a type is its number in decimal ("3601").
constexpr std::optional<ModuleType> module_type_from_name(std::string_view s) noexcept {
  if (s.empty() || s.size() > 9) return std::nullopt;
  std::uint32_t n = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return std::nullopt;
    n = n * 10 + static_cast<std::uint32_t>(c - '0');
  }
  if (s.front() == '0') return std::nullopt;
  return module_type_from_number(n);
}

}  // namespace stepmod

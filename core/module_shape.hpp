#pragma once
// The module types stepmod emulates and the shape of each one's I/O image (docs/interface.md
// section 3 header fields): stated here once, read by the daemon, the PLC-side client, the config
// checker and the module layer.
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

// The terminals of one axis that only some module types have (the config checker refuses a line
// the module has not; the registry checks them against the row's rules value).
struct AxisTerminals {
  bool gpo = false;      // a general-purpose output
  bool estop = false;    // a separate E-stop input
  bool encoder = false;  // quadrature encoder inputs (A, B, Z)
};

// Static facts of a module type.
struct ModuleShape {
  ModuleType type;
  unsigned axes;                   // axes (3601, 3602) or channels (3202)
  unsigned word_bytes;             // 2 or 4
  unsigned output_words;           // PLC -> module
  unsigned input_words;            // module -> PLC
  const char* unit_noun = "axis";  // what its manual calls one unit: "axis" or "channel"
  // The module's digit in an error reason's item code (module/axis/error_reason.hpp); stable,
  // never reused for another type.
  unsigned reason_digit = 0;
  AxisTerminals terminals{};
};

// The image shape of every module type: the ground columns of its registry row
// (registry/module_registry.cpp), here because ipc/, plc/ and the config checker need them and
// sit below the registry. The one place a module's shape is written down.
inline constexpr std::array<ModuleShape, 3> kModuleShapes = {{
    {ModuleType::k3601, 1, 2, 8, 8, "axis", 1, {.gpo = false, .estop = true, .encoder = true}},
    {ModuleType::k3602, 2, 2, 16, 16, "axis", 2, {.gpo = true, .estop = false, .encoder = false}},
    {ModuleType::k3202, 2, 4, 16, 16, "channel", 3, {.gpo = false, .estop = true, .encoder = true}},
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

// The position of `t` in kModuleShapes (a column index of per-module tables such as the error
// items' numbers); kModuleShapes.size() for a number that is no module type.
constexpr std::size_t module_index(ModuleType t) noexcept {
  std::size_t i = 0;
  while (i < kModuleShapes.size() && kModuleShapes[i].type != t) ++i;
  return i;
}

// The module type whose error-reason digit is `digit`, if any.
constexpr std::optional<ModuleType> module_type_from_reason_digit(unsigned digit) noexcept {
  for (const ModuleShape& s : kModuleShapes) {
    if (digit != 0 && s.reason_digit == digit) return s.type;
  }
  return std::nullopt;
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

#pragma once
// 3202 configuration words of one channel (configuration mode, DINTs b+0..b+7, 3202 manual ch. 3):
// validation against the manual's list of invalid configurations (Ch.3 "Invalid Configurations"
// #1..#11 = checklist items 3202-CFG-02..12), the disable bit 28 (3202-CFG-13), and the translation
// of a valid configuration into the shared axis' AxisConfig.
#include <cstdint>
#include <string_view>

#include "core/module_shape.hpp"
#include "module/axis/axis_config.hpp"

namespace stepmod::module::m3202 {

struct Config3202 {
  std::uint32_t bits = 0;           // configuration bits as written (mode bit included)
  std::int32_t starting_speed = 0;  // steps/s

  bool has(std::uint32_t bit) const noexcept { return (bits & bit) != 0; }
};

// The manual's invalid-configuration list, item by item. kNone = valid.
// Alike the 3601 enum (config_3601.hpp) on purpose: the same list, but each has its own item ids.
enum class ConfigFault : std::uint8_t {
  kNone = 0,
  kNoHoming,                   // #1  (3202-CFG-02)
  kNoEndLimit,                 // #2  (3202-CFG-03)
  kEncoderAndDiagnostic,       // #3  (3202-CFG-04)
  kMarkerWithoutEncoder,       // #4  (3202-CFG-05)
  kDiagnosticWithCwCcw,        // #5  (3202-CFG-06)
  kStartingSpeedRange,         // #6  (3202-CFG-07)
  kReservedBits,               // #8  (3202-CFG-09)
  kMarkerWithoutProximity,     // #9  (3202-CFG-10)
  kMarkerWithBothProximities,  // #10 (3202-CFG-11)
  kUnusedWordsNonZero,         // #11 (3202-CFG-12)
};
std::string_view describe(ConfigFault f) noexcept;
// The number of its item in the Configuration Error checklist (3202-CFG-nn; 0 for kNone): the
// error reason's item (docs/error-reasons.md).
unsigned checklist_item(ConfigFault f) noexcept;

struct ConfigCheck {
  ConfigFault fault = ConfigFault::kNone;
  Config3202 config;  // meaningful when fault == kNone
};

// Checks the eight configuration-mode output DINTs of channel `channel` (0 or 1).
ConfigCheck check_config(const ImageWords& out, unsigned channel) noexcept;

// The decoded configuration of a valid 3202 channel configuration.
axis::AxisConfig to_axis_config(const Config3202& c) noexcept;

}  // namespace stepmod::module::m3202

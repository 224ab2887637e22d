#pragma once
// 3602 configuration words of one axis (configuration mode, the axis' eight output words b+0 ..
// b+7 moved to 0..7): validation against the manual's invalid configurations (3602 manual Ch.8
// Tables 8.6/8.7, "Starting Speed", "Homing Timeout", "Reserved Words"; checklist 3602-CFG-01..08
// 3602-CFG-02..08) and the translation of a valid one into the shared axis' AxisConfig. The
// configuration bits are reconstructed from Table 8.2 (its bit columns are garbled in the manual),
// named in words_3602.hpp.
#include <cstdint>
#include <string_view>

#include "core/module_shape.hpp"
#include "module/axis/axis_config.hpp"

namespace stepmod::module::m3602 {

struct Config3602 {
  std::uint16_t msw = 0;              // configuration bits MSW, as written (mode bit included)
  std::uint16_t lsw = 0;              // input active levels
  std::int32_t starting_speed = 0;    // steps/s
  std::int32_t homing_timeout_s = 0;  // 0 = none
};

// The manual's invalid-configuration list, item by item. kNone = valid.
enum class ConfigFault : std::uint8_t {
  kNone = 0,
  kReservedMswBits,     // 3602-CFG-02: bits 8, 9, 11, 12, 13
  kCwInputFunction,     // 3602-CFG-03: CW field = 11
  kCcwInputFunction,    // 3602-CFG-04: CCW field = 11
  kReservedLswBits,     // 3602-CFG-05: LSW bits 5..15
  kStartingSpeedRange,  // 3602-CFG-06: Vs 0, above 1,000,000 or negative
  kHomingTimeoutRange,  // 3602-CFG-07: above 300 or negative
  kReservedWords,       // 3602-CFG-08: words 5..7 not 0
};
std::string_view describe(ConfigFault f) noexcept;
// The number of its item in the Configuration Error checklist (3602-CFG-nn; 0 for kNone): the
// error reason's item (docs/error-reasons.md).
unsigned checklist_item(ConfigFault f) noexcept;

// Checks the eight configuration-mode output words of one axis.
ConfigFault check_config(const ImageWords& out, Config3602& decoded) noexcept;

// The decoded configuration of a valid 3602 configuration.
axis::AxisConfig to_axis_config(const Config3602& c) noexcept;

}  // namespace stepmod::module::m3602

#pragma once
// 3601 configuration words (configuration mode, output words 0..7): validation against the
// manual's list of invalid configurations (Ch.3 "Invalid Configurations" #1..#11, the 3601
// checklist 3601-CFG-02..12), and the translation of a valid one into the shared axis' AxisConfig.
#include <cstdint>
#include <optional>
#include <string_view>

#include "core/module_shape.hpp"
#include "module/axis/axis_config.hpp"

namespace stepmod::module::m3601 {

struct Config3601 {
  std::uint16_t msw = 0;    // configuration bits MSW, as written (mode bit included)
  std::uint16_t lsw = 0;    // input active levels
  std::int16_t vs_msw = 0;  // starting speed words, as written (for the mirror)
  std::int16_t vs_lsw = 0;
  std::int32_t starting_speed = 0;  // steps/s

  bool has(std::uint16_t cfg_msw_bit) const noexcept { return (msw & cfg_msw_bit) != 0; }
};

// The manual's invalid-configuration list, item by item. kNone = valid.
enum class ConfigFault : std::uint8_t {
  kNone = 0,
  kNoHoming,                   // #1  (3601-CFG-02)
  kNoEndLimit,                 // #2  (3601-CFG-03)
  kEncoderAndDiagnostic,       // #3  (3601-CFG-04)
  kMarkerWithoutEncoder,       // #4  (3601-CFG-05)
  kDiagnosticWithCwCcw,        // #5  (3601-CFG-06)
  kStartingSpeedRange,         // #6  (3601-CFG-07)
  kStartingSpeedLswRange,      // #7  (3601-CFG-08)
  kReservedBits,               // #8  (3601-CFG-09)
  kMarkerWithoutProximity,     // #9  (3601-CFG-10)
  kMarkerWithBothProximities,  // #10 (3601-CFG-11)
  kUnusedWordsNonZero,         // #11 (3601-CFG-12)
};
std::string_view describe(ConfigFault f) noexcept;
// The number of its item in the Configuration Error checklist (3601-CFG-nn; 0 for kNone): the
// error reason's item (docs/error-reasons.md).
unsigned checklist_item(ConfigFault f) noexcept;

struct ConfigCheck {
  ConfigFault fault = ConfigFault::kNone;
  Config3601 config;  // meaningful when fault == kNone
};

// Checks the eight configuration-mode output words.
ConfigCheck check_config(const ImageWords& out) noexcept;

// The decoded configuration of a valid 3601 configuration.
axis::AxisConfig to_axis_config(const Config3601& c) noexcept;

}  // namespace stepmod::module::m3601

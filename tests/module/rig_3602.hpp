#pragma once
// A PLC program's view of a 3602 in virtual time: both axes' words written the way a PLC writes
// them (binary split, 3602 manual ch. 9), the module scanning, status read back per axis.
#include <gtest/gtest.h>

#include <cstdint>

#include "tests/support/virtual_machine.hpp"
#include "module_types/m3602/words_3602.hpp"

namespace stepmod::testing {

namespace m2 = words::m3602;

// A machine with two 3602 axes: every input wired, limits at +-100,000, home 5,000..5,100 on
// axis 1 and -3,000..-2,900 on axis 2; a GPO line per axis.
inline VirtualMachineOptions default_3602() {
  VirtualMachineOptions o;
  o.type = ModuleType::k3602;
  unsigned offset = 0;
  for (unsigned a = 0; a < 2; ++a) {
    gpio::SimAxisSetup s;
    for (auto& line : s.lines.out) line = offset++;
    for (auto& line : s.lines.in) line = offset++;
    s.sim.cw_limit_at = 100'000;
    s.sim.ccw_limit_at = -100'000;
    s.sim.home_from = a == 0 ? 5'000 : -3'000;
    s.sim.home_to = a == 0 ? 5'100 : -2'900;
    o.axes.push_back(s);
  }
  return o;
}

// Home, capture and external enabled, both CW/CCW inputs as overtravel limits, step/direction,
// every input active high.
inline constexpr std::uint16_t kLimitsConfigMsw =
    m2::cfg_msw::kCaptureEnabled | m2::cfg_msw::kExternalEnabled | m2::cfg_msw::kHomeEnabled |
    (m2::cfg_msw::kFunctionLimit << m2::cfg_msw::kCwFunctionShift) |
    (m2::cfg_msw::kFunctionLimit << m2::cfg_msw::kCcwFunctionShift) | m2::cfg_msw::kStepDirOutput;
inline constexpr std::uint16_t kAllActiveHigh3602 = 0x001F;

struct Move3602 {
  std::int32_t target = 0;
  std::int32_t speed = 10'000;
  std::int16_t accel = 10;  // steps/ms/s
  std::int16_t decel = 10;
  std::uint16_t lsw = 0;
};

class Rig3602 : public ::testing::Test {
 protected:
  Rig3602() : vm_(default_3602()) {}

  static constexpr unsigned kAxis1 = 0;
  static constexpr unsigned kAxis2 = 1;

  std::int32_t& word(unsigned axis, unsigned i) { return vm_.plc_out().w[8 * axis + i]; }
  std::int32_t in_word(unsigned axis, unsigned i) const { return vm_.plc_in().w[8 * axis + i]; }
  std::uint16_t status_msw(unsigned axis) const {
    return static_cast<std::uint16_t>(in_word(axis, m2::in_word::kStatusMsw));
  }
  std::uint16_t status_lsw(unsigned axis) const {
    return static_cast<std::uint16_t>(in_word(axis, m2::in_word::kStatusLsw));
  }
  bool status(unsigned axis, std::uint16_t msw_bit) const {
    return (status_msw(axis) & msw_bit) != 0;
  }
  bool lsw_status(unsigned axis, std::uint16_t lsw_bit) const {
    return (status_lsw(axis) & lsw_bit) != 0;
  }
  std::int32_t split_in(unsigned axis, unsigned msw_index) const {
    return words::decode_3602(in_word(axis, msw_index), in_word(axis, msw_index + 1));
  }
  std::int32_t position(unsigned axis) const { return split_in(axis, m2::in_word::kPositionMsw); }
  std::int32_t capture(unsigned axis) const { return split_in(axis, m2::in_word::kCaptureMsw); }
  std::int64_t motor(unsigned axis) { return vm_.sim().position(axis); }
  bool moving(unsigned axis) const {
    return status(axis, m2::status_msw::kMovingCw) || status(axis, m2::status_msw::kMovingCcw);
  }

  void put_split(unsigned axis, unsigned msw_index, std::int32_t v) {
    const auto p = words::encode_3602(v);
    word(axis, msw_index) = p.msw;
    word(axis, msw_index + 1) = p.lsw;
  }
  void clear_words(unsigned axis) {
    for (unsigned i = 0; i < 8; ++i) word(axis, i) = 0;
  }
  // Configuration words of one axis, mode bit set (3602 manual ch. 8 table 8.1).
  void write_config(unsigned axis, std::uint16_t msw, std::uint16_t lsw = kAllActiveHigh3602,
                    std::int32_t starting_speed = 1'000, std::int16_t homing_timeout = 0) {
    clear_words(axis);
    word(axis, m2::out_word::kMsw) = static_cast<std::int16_t>(msw | m2::cfg_msw::kConfigMode);
    word(axis, m2::out_word::kLsw) = static_cast<std::int16_t>(lsw);
    put_split(axis, m2::out_word::kStartingSpeedMsw, starting_speed);
    word(axis, m2::out_word::kHomingTimeout) = homing_timeout;
  }
  // Configuration mode for 3 scans, then command mode with the axis' words 0.
  void configure(unsigned axis, std::uint16_t msw = kLimitsConfigMsw,
                 std::uint16_t lsw = kAllActiveHigh3602, std::int32_t starting_speed = 1'000,
                 std::int16_t homing_timeout = 0) {
    write_config(axis, msw, lsw, starting_speed, homing_timeout);
    vm_.scans(3);
    clear_words(axis);
    vm_.scans(3);
  }
  void set_command(unsigned axis, std::uint16_t msw, const Move3602& p = {}) {
    word(axis, m2::out_word::kMsw) = static_cast<std::int16_t>(msw);
    word(axis, m2::out_word::kLsw) = static_cast<std::int16_t>(p.lsw);
    put_split(axis, m2::out_word::kTargetMsw, p.target);
    put_split(axis, m2::out_word::kSpeedMsw, p.speed);
    word(axis, m2::out_word::kAccel) = p.accel;
    word(axis, m2::out_word::kDecel) = p.decel;
  }
  // An edge-triggered command the way a PLC issues it: bit set for 3 scans, then cleared (the
  // other words stay, as a PLC leaves them).
  void command(unsigned axis, std::uint16_t msw, const Move3602& p = {}) {
    set_command(axis, msw, p);
    vm_.scans(3);
    word(axis, m2::out_word::kMsw) = 0;
    vm_.scans(1);
  }
  bool wait_idle(unsigned axis, Nanos limit = 30 * kNsPerSec) {
    return vm_.run_until_true([this, axis] { return !moving(axis); }, limit);
  }

  VirtualMachine vm_;
};

}  // namespace stepmod::testing

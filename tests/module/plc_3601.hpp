#pragma once
// A PLC program's view of a 3601 in virtual time: write words, let the module scan, read status.
// The words and their sequencing are the PLC-side library's (module_types/m3601/plc_3601.hpp) over the virtual
// machine's port; this fixture only keeps the names the module tests are written in.
#include <gtest/gtest.h>

#include <cstdint>

#include "module_types/m3601/plc_3601.hpp"
#include "tests/support/virtual_machine.hpp"
#include "tests/support/virtual_port.hpp"
#include "module_types/m3601/words_3601.hpp"

namespace stepmod::testing {

namespace m = words::m3601;

// A configuration every test can start from: home input + both limits + E-stop + external +
// capture + encoder, step/direction outputs, all inputs active high, Vs = 1,000 steps/s.
inline constexpr std::uint16_t kFullConfigMsw =
    m::cfg_msw::kCaptureUsed | m::cfg_msw::kExternalUsed | m::cfg_msw::kHomeUsed |
    m::cfg_msw::kEStopUsed | m::cfg_msw::kCwLimitUsed | m::cfg_msw::kCcwLimitUsed |
    m::cfg_msw::kQuadratureEncoder | m::cfg_msw::kStepDirOutput;
inline constexpr std::uint16_t kAllActiveHigh = 0x003F;

// The scan counts the module tests' timing assertions were written for: a command's words for 3
// scans, 1 scan after its release; 3 scans in configuration mode and 3 back in command mode. The
// tests set bits on purpose, so nothing is released behind their back.
inline constexpr plc::Sequencing kFixtureSequencing{
    .hold_scans = 3, .release_scans = 1, .config_scans = 3, .release_stale_bits = false};

struct Move {
  std::int32_t target = 0;
  std::int32_t speed = 10'000;
  std::int16_t accel = 10;  // steps/ms/s
  std::int16_t decel = 10;
  std::uint16_t lsw = 0;
};

class Plc3601 : public ::testing::Test {
 protected:
  Plc3601() : vm_(default_3601()) {}
  explicit Plc3601(VirtualMachineOptions o) : vm_(std::move(o)) {}

  std::int32_t& word(unsigned i) { return vm_.plc_out().w[i]; }
  plc::m3601::Status decoded() const { return plc::m3601::decode_status(vm_.plc_in()); }
  std::uint16_t status_msw() const { return decoded().msw; }
  std::uint16_t status_lsw() const { return decoded().lsw; }
  bool status(std::uint16_t msw_bit) const { return decoded().has(msw_bit); }
  bool lsw_status(std::uint16_t lsw_bit) const { return decoded().has_lsw(lsw_bit); }
  std::int64_t reported(unsigned msw_index) const {
    return words::decode_3601_report(vm_.plc_in().w[msw_index], vm_.plc_in().w[msw_index + 1]);
  }
  std::int64_t position() const { return decoded().position; }
  std::int64_t encoder() const { return decoded().encoder; }
  std::int64_t capture() const { return decoded().capture; }
  std::int64_t motor() { return vm_.sim().position(0); }

  void set_words(std::uint16_t msw, std::uint16_t lsw, std::int32_t w23, std::int32_t w45,
                 std::int16_t w6, std::int16_t w7) {
    port_.write_outputs(plc::m3601::command_words(msw, lsw, w23, w45, w6, w7));
  }

  // Writes a configuration, lets the module take it, returns to command mode.
  void configure(std::uint16_t msw = kFullConfigMsw, std::uint16_t lsw = kAllActiveHigh,
                 std::int32_t starting_speed = 1'000) {
    plc_.configure(msw, lsw, starting_speed);  // then command mode, all words 0
  }
  void write_config(std::uint16_t msw, std::uint16_t lsw, std::int32_t starting_speed) {
    port_.write_outputs(plc::m3601::configuration_words(msw, lsw, starting_speed));
  }
  // Issues an edge-triggered command the way a PLC does: bit set for a few scans, then cleared.
  void command(std::uint16_t msw_bit, const Move& p = {}) {
    plc_.pulse(plc::m3601::command_words(msw_bit, p.lsw, p.target, p.speed, p.accel, p.decel),
               msw_bit);
  }
  // Only word 0 changes: the other words stay as the test left them.
  void raw_command(std::uint16_t msw_bit) { plc_.pulse_msw(msw_bit); }
  bool moving() const { return decoded().moving(); }
  // Runs until the axis is at rest (not moving), at most `limit`.
  bool wait_idle(Nanos limit = 30 * kNsPerSec) {
    return port_.wait_inputs(
        [](const ImageWords& in) { return !plc::m3601::decode_status(in).moving(); },
        std::chrono::nanoseconds(limit));
  }
  // Panel: force an input's electrical level (docs/interface.md section 4 bit order).
  void force(InputLine l, bool level) {
    forced_mask_ |= 1u << static_cast<unsigned>(l);
    if (level) {
      forced_levels_ |= 1u << static_cast<unsigned>(l);
    } else {
      forced_levels_ &= ~(1u << static_cast<unsigned>(l));
    }
    vm_.sim().force(0, forced_mask_, forced_levels_, vm_.now());
  }
  void release(InputLine l) {
    forced_mask_ &= ~(1u << static_cast<unsigned>(l));
    vm_.sim().force(0, forced_mask_, forced_levels_, vm_.now());
  }

  VirtualMachine vm_;
  VirtualPort port_{vm_};
  plc::Plc3601 plc_{port_, std::chrono::milliseconds(2000), kFixtureSequencing};
  std::uint32_t forced_mask_ = 0;
  std::uint32_t forced_levels_ = 0;
};

}  // namespace stepmod::testing

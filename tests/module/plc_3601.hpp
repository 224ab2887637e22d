#pragma once
// A PLC program's view of a 3601 in virtual time: write words, let the module scan, read status.
#include <gtest/gtest.h>

#include <cstdint>

#include "ipc/codec.hpp"
#include "module/m3601/words_3601.hpp"
#include "tests/support/virtual_machine.hpp"

namespace stepmod::testing {

namespace m = module::m3601;

// A configuration every test can start from: home input + both limits + E-stop + external +
// capture + encoder, step/direction outputs, all inputs active high, Vs = 1,000 steps/s.
inline constexpr std::uint16_t kFullConfigMsw =
    m::cfg_msw::kCaptureUsed | m::cfg_msw::kExternalUsed | m::cfg_msw::kHomeUsed |
    m::cfg_msw::kEStopUsed | m::cfg_msw::kCwLimitUsed | m::cfg_msw::kCcwLimitUsed |
    m::cfg_msw::kQuadratureEncoder | m::cfg_msw::kStepDirOutput;
inline constexpr std::uint16_t kAllActiveHigh = 0x003F;

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
  std::uint16_t status_msw() const { return static_cast<std::uint16_t>(vm_.plc_in().w[0]); }
  std::uint16_t status_lsw() const { return static_cast<std::uint16_t>(vm_.plc_in().w[1]); }
  bool status(std::uint16_t msw_bit) const { return (status_msw() & msw_bit) != 0; }
  bool lsw_status(std::uint16_t lsw_bit) const { return (status_lsw() & lsw_bit) != 0; }
  std::int64_t reported(unsigned msw_index) const {
    return ipc::codec::decode_3601_report(vm_.plc_in().w[msw_index], vm_.plc_in().w[msw_index + 1]);
  }
  std::int64_t position() const { return reported(m::in_word::kPositionMsw); }
  std::int64_t encoder() const { return reported(m::in_word::kEncoderMsw); }
  std::int64_t capture() const { return reported(m::in_word::kCaptureMsw); }
  std::int64_t motor() { return vm_.sim().position(0); }

  void set_words(std::uint16_t msw, std::uint16_t lsw, std::int32_t w23, std::int32_t w45,
                 std::int16_t w6, std::int16_t w7) {
    auto a = ipc::codec::encode_3601(w23);
    auto b = ipc::codec::encode_3601(w45);
    auto& o = vm_.plc_out().w;
    o = {};
    o[0] = static_cast<std::int16_t>(msw);
    o[1] = static_cast<std::int16_t>(lsw);
    o[2] = a.msw;
    o[3] = a.lsw;
    o[4] = b.msw;
    o[5] = b.lsw;
    o[6] = w6;
    o[7] = w7;
  }

  // Writes a configuration, lets the module take it, returns to command mode.
  void configure(std::uint16_t msw = kFullConfigMsw, std::uint16_t lsw = kAllActiveHigh,
                 std::int32_t starting_speed = 1'000) {
    write_config(msw, lsw, starting_speed);
    vm_.scans(3);
    word(0) = 0;  // command mode
    for (unsigned i = 1; i < 8; ++i) word(i) = 0;
    vm_.scans(3);
  }
  void write_config(std::uint16_t msw, std::uint16_t lsw, std::int32_t starting_speed) {
    set_words(static_cast<std::uint16_t>(msw | m::cfg_msw::kConfigMode), lsw, starting_speed, 0, 0,
              0);
  }
  // Issues an edge-triggered command the way a PLC does: bit set for a few scans, then cleared.
  void command(std::uint16_t msw_bit, const Move& p = {}) {
    set_words(msw_bit, p.lsw, p.target, p.speed, p.accel, p.decel);
    vm_.scans(3);
    word(0) = 0;
    vm_.scans(1);
  }
  void raw_command(std::uint16_t msw_bit) {
    word(0) = static_cast<std::int16_t>(msw_bit);
    vm_.scans(3);
    word(0) = 0;
    vm_.scans(1);
  }
  bool moving() const {
    return status(m::status_msw::kMovingCw) || status(m::status_msw::kMovingCcw);
  }
  // Runs until the axis is at rest (not moving), at most `limit`.
  bool wait_idle(Nanos limit = 30 * kNsPerSec) {
    return vm_.run_until_true([this] { return !moving(); }, limit);
  }
  // Panel: force an input's electrical level (INTERFACE.md section 4 bit order).
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
  std::uint32_t forced_mask_ = 0;
  std::uint32_t forced_levels_ = 0;
};

}  // namespace stepmod::testing

#pragma once
// A PLC program's view of a 3202 in virtual time: two channels of eight DINTs each (channel 1 in
// DINTs 0..7, channel 2 in 8..15), written as a ControlLogix program writes them, the module
// scanning them, the status read back per channel. Channels are 0 and 1 here (the manual's 1
// and 2).
#include <gtest/gtest.h>

#include <cstdint>

#include "module_types/m3202/plc_words_3202.hpp"
#include "tests/support/virtual_machine.hpp"
#include "module_types/m3202/words_3202.hpp"

namespace stepmod::testing {

namespace m2 = words::m3202;

// Home input + both limits + E-stop + external + capture + encoder, step/direction outputs, all
// inputs active high, per channel.
inline constexpr std::uint32_t kFull3202 =
    m2::cfg_bit::kCaptureUsed | m2::cfg_bit::kExternalUsed | m2::cfg_bit::kHomeUsed |
    m2::cfg_bit::kEStopUsed | m2::cfg_bit::kCwLimitUsed | m2::cfg_bit::kCcwLimitUsed |
    m2::cfg_bit::kQuadratureEncoder | m2::cfg_bit::kStepDirOutput | m2::cfg_bit::kActiveLevels;

// Two identical machines (limits at +-100,000, home 5,000..5,100, marker every 4,000).
inline VirtualMachineOptions default_3202() {
  VirtualMachineOptions o = default_3601();
  o.type = ModuleType::k3202;
  o.axes.push_back(o.axes[0]);
  return o;
}

struct Move3202 {
  std::int32_t target = 0;
  std::int32_t speed = 10'000;
  std::int32_t accel = 10'000;  // steps/s^2 (A31)
  std::int32_t decel = 10'000;
  std::uint32_t flags = 0;  // bits 16/17/18/29 of the command word
};

class Plc3202 : public ::testing::Test {
 protected:
  Plc3202() : vm_(default_3202()) {}
  explicit Plc3202(VirtualMachineOptions o) : vm_(std::move(o)) {}

  std::int32_t& word(unsigned ch, unsigned i) { return vm_.plc_out().w[ch * 8 + i]; }
  std::int32_t in(unsigned ch, unsigned i) const { return vm_.plc_in().w[ch * 8 + i]; }
  std::uint32_t status_word(unsigned ch) const { return static_cast<std::uint32_t>(in(ch, 0)); }
  bool status(unsigned ch, std::uint32_t bit) const { return (status_word(ch) & bit) != 0; }
  std::int32_t position(unsigned ch) const { return in(ch, m2::in_word::kPosition); }
  std::int32_t encoder(unsigned ch) const { return in(ch, m2::in_word::kEncoder); }
  std::int32_t capture(unsigned ch) const { return in(ch, m2::in_word::kCapture); }
  std::int64_t motor(unsigned ch) { return vm_.sim().position(ch); }
  bool moving(unsigned ch) const {
    return status(ch, m2::status_bit::kMovingCw | m2::status_bit::kMovingCcw);
  }

  void put(unsigned ch, const plc::m3202::ChannelWords& w) {
    for (unsigned i = 0; i < 8; ++i) word(ch, i) = w[i];
  }
  void write_config(unsigned ch, std::uint32_t bits, std::int32_t vs = 1'000) {
    put(ch, plc::m3202::configuration_words(bits, vs));
  }
  // Configuration mode for 3 scans, then command mode (all words 0) for 3 scans.
  void configure(unsigned ch, std::uint32_t bits = kFull3202, std::int32_t vs = 1'000) {
    write_config(ch, bits, vs);
    vm_.scans(3);
    put(ch, {});
    vm_.scans(3);
  }
  void set_command(unsigned ch, std::uint32_t bits, const Move3202& p = {}) {
    put(ch, plc::m3202::command_words(bits | p.flags, p.target, p.speed, p.accel, p.decel));
  }
  // An edge-triggered command: its words for 3 scans, then the command bits cleared for 1.
  void command(unsigned ch, std::uint32_t bit, const Move3202& p = {}) {
    set_command(ch, bit, p);
    vm_.scans(3);
    word(ch, 0) &= ~static_cast<std::int32_t>(bit & 0x3FFFu);
    vm_.scans(1);
  }
  bool wait_idle(unsigned ch, Nanos limit = 30 * kNsPerSec) {
    return vm_.run_until_true([&] { return !moving(ch); }, limit);
  }
  void force(unsigned ch, InputLine l, bool level) {
    const std::uint32_t bit = 1u << static_cast<unsigned>(l);
    mask_[ch] |= bit;
    levels_[ch] = level ? (levels_[ch] | bit) : (levels_[ch] & ~bit);
    vm_.sim().force(ch, mask_[ch], levels_[ch], vm_.now());
  }
  void release(unsigned ch, InputLine l) {
    mask_[ch] &= ~(1u << static_cast<unsigned>(l));
    vm_.sim().force(ch, mask_[ch], levels_[ch], vm_.now());
  }

  VirtualMachine vm_;
  std::uint32_t mask_[2] = {0, 0};
  std::uint32_t levels_[2] = {0, 0};
};

}  // namespace stepmod::testing

#pragma once
// A PLC program writing the 3602's interpolated moves (3602 manual tables 9.4, 9.23-9.26): the
// block in all sixteen output words, the data first with the command bits clear and the bits >= 10
// ms later (the manual's rule for the backplane's 8-word blocks), both axes configured.
#include "tests/module/rig_3602.hpp"

namespace stepmod::testing {

namespace iw = m2::interp_word;
namespace il = m2::cmd_lsw;

struct Path3602 {
  std::uint16_t lsw = il::kLinear;  // bits 9..14, accel type, GPO
  std::int32_t speed = 10'000;      // vector speed, steps/s
  std::int16_t accel = 10;          // vector accel / decel, steps/ms/s
  std::int16_t decel = 10;
  std::int32_t end_x = 0;
  std::int32_t end_y = 0;
  std::int32_t point_x = 0;  // via X / centre X / signed radius
  std::int32_t point_y = 0;  // via Y / centre Y
};

class RigInterp3602 : public Rig3602 {
 protected:
  void SetUp() override {
    configure(kAxis1);
    configure(kAxis2);
  }
  std::int32_t& module_word(unsigned i) { return vm_.plc_out().w[i]; }
  void put_module_split(unsigned i, std::int32_t v) {
    const auto p = words::encode_3602(v);
    module_word(i) = p.msw;
    module_word(i + 1) = p.lsw;
  }
  // The block in all sixteen words; `bits`: with the interpolation bits 9..14 of the LSW.
  void write_path(const Path3602& p, bool bits) {
    clear_words(kAxis1);
    clear_words(kAxis2);
    module_word(iw::kLsw) = static_cast<std::int16_t>(bits ? p.lsw : p.lsw & ~il::kInterpolation);
    put_module_split(iw::kSpeedMsw, p.speed);
    module_word(iw::kAccel) = p.accel;
    module_word(iw::kDecel) = p.decel;
    put_module_split(iw::kEndXMsw, p.end_x);
    put_module_split(iw::kEndYMsw, p.end_y);
    put_module_split(iw::kPointXMsw, p.point_x);
    put_module_split(iw::kPointYMsw, p.point_y);
  }
  void set_bits(std::uint16_t lsw) { module_word(iw::kLsw) = static_cast<std::int16_t>(lsw); }
  void clear_bits() {
    module_word(iw::kLsw) = static_cast<std::int16_t>(
        static_cast<std::uint16_t>(module_word(iw::kLsw)) & ~il::kInterpolation);
  }
  // The manual's sequence: data with the bits clear, 10 ms, the bits for 3 scans, released.
  void path_command(const Path3602& p) {
    write_path(p, false);
    vm_.scans(10);
    set_bits(p.lsw);
    vm_.scans(3);
    clear_bits();
    vm_.scans(1);
  }
  void reset_errors(unsigned a) {
    clear_words(a);
    command(a, m2::cmd_msw::kResetErrors, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  }
  void preset(unsigned a, std::int32_t p) {
    clear_words(a);
    command(a, m2::cmd_msw::kPresetPosition, {.target = p, .speed = 0, .accel = 0, .decel = 0});
  }
  void force(unsigned a, InputLine l, bool level) {
    const std::uint32_t bit = 1u << static_cast<unsigned>(l);
    if (level) {
      levels_[a] |= bit;
    } else {
      levels_[a] &= ~bit;
    }
    mask_[a] |= bit;
    vm_.sim().force(a, mask_[a], levels_[a], vm_.now());
    vm_.scans(2);
  }
  bool path_idle() const {
    return status(kAxis1, m2::status_msw::kStopped) && status(kAxis2, m2::status_msw::kStopped);
  }
  bool wait_path_end(Nanos limit = 30 * kNsPerSec) {
    return vm_.run_until_true([this] { return path_idle(); }, limit);
  }
  bool ce(unsigned a) const { return status(a, m2::status_msw::kCommandError); }
  bool ip(unsigned a) const { return status(a, m2::status_msw::kInvalidProfile); }

  std::uint32_t mask_[2] = {0, 0};
  std::uint32_t levels_[2] = {0, 0};
};

}  // namespace stepmod::testing

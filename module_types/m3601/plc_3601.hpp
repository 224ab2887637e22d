#pragma once
// The 3601 as a PLC program drives it, over any Port: each command is written the way a PLC
// program does it (parameter words + command bit, wait until the module has scanned it, release
// the edge-triggered bit), then the status is read back. Used by stepmodctl and by every test.
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "module_types/m3601/plc_status_3601.hpp"
#include "module_types/m3601/plc_words_3601.hpp"
#include "plc/driver.hpp"
#include "plc/move_profile.hpp"
#include "plc/port.hpp"

namespace stepmod::plc {

class Plc3601 : public Driver<ModuleType::k3601, words::m3601::kStatusMswBits, m3601::status_msw> {
 public:
  // Throws std::invalid_argument if the port's module is not a 3601 (plc/driver.hpp).
  using Driver::Driver;

  // Configuration mode: config bits MSW (bit 15 is added), active levels LSW and starting speed;
  // then back to command mode (all words 0). Error: Configuration Error. `in_config` receives the
  // input image read in configuration mode (the echo and its verdict).
  Outcome configure(std::uint16_t cfg_msw, std::uint16_t cfg_lsw, std::int32_t start_speed,
                    ImageWords* in_config = nullptr);
  Outcome move(bool absolute, std::int32_t target, const Profile& p, bool encoder_move = false);
  // Manual move (level-held bit) for `duration`, then released and waited until stopped.
  // `registration` > 0 makes it a registration move (3601 manual ch. 4).
  Outcome jog(bool cw, const Profile& p, std::chrono::milliseconds duration,
              std::int32_t registration = 0);
  // The same as a PLC holding the button: jog_press sets the level-held bit and returns once
  // the module scanned it; jog_release clears it (the axis decelerates to a stop, as the manual
  // says of a released Manual bit). For an operator's button (stepmod-web).
  Outcome jog_press(bool cw, const Profile& p, std::int32_t registration = 0);
  Outcome jog_release();
  Outcome home(bool cw, const Profile& p);
  Outcome hold();
  // Without a profile the speed/accel/decel words of the previous move stay as they are.
  Outcome resume(const std::optional<Profile>& p);
  Outcome immediate_stop();
  Outcome preset_position(std::int32_t position);
  Outcome preset_encoder(std::int32_t value);
  Outcome reset_errors();
  Outcome set_min_registration(std::int32_t distance);
  // Blend programming handshake (3601 manual ch. 4-5): program bit held, one transmit edge per
  // block, each acknowledged by the module.
  Outcome blend_program(const BlendProfile& b);
  Outcome blend_run(bool cw);
  // Encoder follower mode (3601 manual ch. 4): the follower words stay written (the direction bit
  // is a level) until end_follow(). `sense`: +1 same sense as the master, -1 reverse, 0 follower
  // mode without motion. Multiplier and divisor 1..32767 each.
  Outcome follow(int sense, std::int16_t multiplier, std::int16_t divisor, std::int16_t accel,
                 std::int16_t decel);
  // Leaves follower mode: follower bit and direction bit released (all words 0).
  Outcome end_follow();
  // Waits until neither Moving CW/CCW nor Blend Running is set.
  Outcome wait_idle(std::chrono::nanoseconds timeout);
  // The input image now.
  Outcome status();

  // An edge-triggered command as given: `words` written as one write, held for hold_scans, then
  // the `edge_bits` of word 0 cleared and release_scans waited. Errors: Command Error, Invalid
  // Profile.
  Outcome pulse(const ImageWords& words, std::uint16_t edge_bits);
  // The same with only word 0 changed to `msw` (the other words stay as they are).
  Outcome pulse_msw(std::uint16_t msw);

 private:
  // Makes sure none of `bits` is set in output word `word` (so the next set is a 0->1 edge).
  bool release_bits(unsigned word, std::uint16_t bits);
  bool release_stale();
  Outcome edge_command(const ImageWords& words, std::uint16_t edge_bit, std::uint32_t error_mask);
  // The answer of the one axis (plc/driver.hpp).
  Outcome finish(std::uint32_t error_mask, bool timed_out, const std::string& what) {
    return Driver::finish(0, error_mask, timed_out, what);
  }
};

}  // namespace stepmod::plc

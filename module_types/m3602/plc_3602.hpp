#pragma once
// The 3602 as a PLC program drives it, over any Port, one axis at a time (axis 0 = the manual's
// axis 1): the axis' parameter words and command bit written as one write, held until the module
// has scanned them, the edge-triggered bit released; the other axis' words are never touched, so
// one axis can be configured or commanded while the other runs (3602 manual).
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>

#include "module_types/m3602/plc_status_3602.hpp"
#include "module_types/m3602/plc_words_3602.hpp"
#include "plc/driver.hpp"
#include "plc/move_profile.hpp"
#include "plc/port.hpp"

namespace stepmod::plc {

class Plc3602 : public Driver<ModuleType::k3602, words::m3602::kStatusMswBits, m3602::status_msw> {
 public:
  // Throws std::invalid_argument if the port's module is not a 3602 (plc/driver.hpp).
  using Driver::Driver;

  // Configuration mode for `axis`, then back to command mode (the axis' words 0). Error:
  // Configuration Error.
  Outcome configure(unsigned axis, std::uint16_t cfg_msw, std::uint16_t cfg_lsw,
                    std::int32_t start_speed, std::int16_t homing_timeout_s = 0);
  Outcome move(unsigned axis, bool absolute, std::int32_t target, const Profile& p);
  // Find Home CW/CCW (constant acceleration only: LSW bit 0 must be 0; words 2/3 0). The
  // backplane proximity bit (command LSW bit 6) is kept as the PLC left it. Errors: Command
  // Error, Invalid Profile, Home Invalid.
  Outcome home(unsigned axis, bool cw, const Profile& p);
  // Jog (level-held bit) for `duration`, released, then waited until stopped. `registration` > 0
  // makes it a registration move of that many steps after the stop trigger (3602 manual table 9.3,
  // bits 7/8).
  Outcome jog(unsigned axis, bool cw, const Profile& p, std::chrono::milliseconds duration,
              std::int32_t registration = 0);
  // The same as a PLC holding the button: jog_press sets the level-held bit and returns once the
  // module scanned it; jog_release clears the axis' MSW (the axis decelerates to a stop).
  Outcome jog_press(unsigned axis, bool cw, const Profile& p, std::int32_t registration = 0);
  Outcome jog_release(unsigned axis);
  // Hold Move: the parameter words stay as they are (the module ignores them).
  Outcome hold(unsigned axis);
  // Resume Move; without a profile the speed/accel/decel words of the held move stay.
  Outcome resume(unsigned axis, const std::optional<Profile>& p);
  Outcome preset_position(unsigned axis, std::int32_t position);
  Outcome reset_errors(unsigned axis);
  Outcome immediate_stop(unsigned axis);
  // Set Minimum Registration Distance: MSW 0, LSW bit 2 (0->1) with the distance in words 2/3.
  Outcome set_min_registration(unsigned axis, std::int32_t distance);
  // Blend programming handshake (3602 manual ch. 9, table 9.2): program bit held, one transmit edge
  // per block, each acknowledged by the axis' Blend Block Acknowledge.
  Outcome blend_program(unsigned axis, const BlendProfile& b);
  Outcome blend_run(unsigned axis, bool cw);
  // The general-purpose output (command LSW bit 7): a level, kept with every later command.
  Outcome set_gpo(unsigned axis, bool on);
  // Waits until `axis` is neither moving nor running a blend.
  Outcome wait_idle(unsigned axis, std::chrono::nanoseconds timeout);
  // An edge-triggered command of `axis`: MSW/LSW and parameters as for put_command (the GPO bit
  // is kept as it is), held for hold_scans, the MSW released, release_scans waited.
  Outcome pulse(unsigned axis, std::uint16_t msw, std::uint16_t lsw, std::int32_t w23,
                std::int32_t w45, std::int16_t w6, std::int16_t w7);

 private:
  // An edge-triggered MSW bit with the axis' other words edited by `edit` (GPO bit kept).
  Outcome edge(unsigned axis, std::uint16_t msw, std::uint32_t error_mask, const char* what,
               const std::function<void(ImageWords&, unsigned base)>& edit);
  bool release_msw(unsigned axis);
  bool set_lsw(unsigned axis, std::uint16_t lsw);
  std::uint16_t gpo_bit(unsigned axis) const;
};

}  // namespace stepmod::plc

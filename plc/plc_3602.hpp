#pragma once
// The 3602 as a PLC program drives it, over any Port, one axis at a time (axis 0 = the manual's
// axis 1): the axis' parameter words and command bit written as one write, held until the module
// has scanned them, the edge-triggered bit released; the other axis' words are never touched, so
// one axis can be configured or commanded while the other runs (digest 4).
#include <chrono>
#include <cstdint>

#include "plc/plc_3601.hpp"  // Sequencing
#include "plc/port.hpp"
#include "plc/profile.hpp"
#include "plc/status_3602.hpp"
#include "plc/words_3602.hpp"

namespace stepmod::plc {

class Plc3602 {
 public:
  // Throws std::invalid_argument if the port's module is not a 3602.
  explicit Plc3602(Port& port, std::chrono::milliseconds timeout = std::chrono::milliseconds(2000),
                   Sequencing seq = {});

  // Configuration mode for `axis`, then back to command mode (the axis' words 0). Error:
  // Configuration Error.
  Outcome configure(unsigned axis, std::uint16_t cfg_msw, std::uint16_t cfg_lsw,
                    std::int32_t start_speed, std::int16_t homing_timeout_s = 0);
  Outcome move(unsigned axis, bool absolute, std::int32_t target, const Profile& p);
  Outcome preset_position(unsigned axis, std::int32_t position);
  Outcome reset_errors(unsigned axis);
  Outcome immediate_stop(unsigned axis);
  // The general-purpose output (command LSW bit 7): a level, kept with every later command.
  Outcome set_gpo(unsigned axis, bool on);
  // Waits until `axis` is not moving.
  Outcome wait_idle(unsigned axis, std::chrono::nanoseconds timeout);
  // An edge-triggered command of `axis`: MSW/LSW and parameters as for put_command (the GPO bit
  // is kept as it is), held for hold_scans, the MSW released, release_scans waited.
  Outcome pulse(unsigned axis, std::uint16_t msw, std::uint16_t lsw, std::int32_t w23,
                std::int32_t w45, std::int16_t w6, std::int16_t w7);

 private:
  Outcome finish(unsigned axis, std::uint16_t error_mask, bool timed_out, const char* what);
  std::uint16_t gpo_bit(unsigned axis) const;

  Port& port_;
  std::chrono::milliseconds timeout_;
  Sequencing seq_;
};

}  // namespace stepmod::plc

#pragma once
// The 3202 as a PLC program drives it, over any Port, one channel at a time (0 = the manual's
// channel 1, 1 = channel 2): parameter DINTs + command bit written together, held until the
// module scanned them, the edge-triggered bit released, the channel's status read back. The
// other channel's DINTs are never touched. Rates are steps/s^2 (A31).
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "module_types/m3202/plc_status_3202.hpp"
#include "module_types/m3202/plc_words_3202.hpp"
#include "plc/driver.hpp"
#include "plc/move_profile.hpp"
#include "plc/port.hpp"

namespace stepmod::plc {

class Plc3202 : public Driver<ModuleType::k3202, words::m3202::kStatusBits, m3202::status_word> {
 public:
  // Throws std::invalid_argument if the port's module is not a 3202 (plc/driver.hpp).
  using Driver::Driver;

  // Configuration mode with these configuration bits (bit 31 is added) and starting speed, then
  // command mode (the channel's DINTs 0). Error: Configuration Error.
  Outcome configure(unsigned ch, std::uint32_t bits, std::int32_t start_speed);
  Outcome move(unsigned ch, bool absolute, std::int32_t target, const Profile& p,
               bool encoder_move = false);
  // Manual move (level-held bit) for `duration`, then released and waited until stopped.
  Outcome jog(unsigned ch, bool cw, const Profile& p, std::chrono::milliseconds duration);
  // The two halves of jog, for a caller that holds the bit itself (a console's jog button):
  // the bit set with the parameters and held until jog_release clears it (the channel then
  // decelerates to a stop, as when a PLC releases the bit).
  Outcome jog_press(unsigned ch, bool cw, const Profile& p);
  Outcome jog_release(unsigned ch);
  Outcome home(unsigned ch, bool cw, const Profile& p);
  Outcome hold(unsigned ch);
  Outcome resume(unsigned ch, const std::optional<Profile>& p);
  Outcome immediate_stop(unsigned ch);
  Outcome preset_position(unsigned ch, std::int32_t position);
  Outcome preset_encoder(unsigned ch, std::int32_t value);
  Outcome reset_errors(unsigned ch);
  Outcome blend_run(unsigned ch, bool cw);
  // Waits until the channel is neither moving nor running a blend.
  Outcome wait_idle(unsigned ch, std::chrono::nanoseconds timeout);
  Outcome status(unsigned ch);

 private:
  Outcome edge_command(unsigned ch, const m3202::ChannelWords& words, std::uint32_t edge_bit,
                       std::uint32_t error_mask);
  void write_channel(unsigned ch, const m3202::ChannelWords& words);
};

}  // namespace stepmod::plc

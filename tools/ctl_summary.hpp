#pragma once
// One axis/channel of any module in a few words (stepmodctl status --brief / --json, wait-idle
// and --wait): its state, position, error bits and the module's reason (INTERFACE 3.4).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/module_shape.hpp"
#include "ipc/stepmod_image.h"

namespace stepmod::tools::ctl {

struct AxisSummary {
  bool configuration_mode = false;
  bool moving_cw = false, moving_ccw = false;
  bool blend_running = false;
  bool hold = false, stopped = false, at_home = false, move_complete = false;
  // Error bits, in the lists' order: CFG, CE, IP, IE, HI, PI.
  bool cfg_error = false, command_error = false, invalid_profile = false, input_error = false,
       home_invalid = false, position_invalid = false;
  std::int64_t position = 0;

  bool moving() const noexcept { return moving_cw || moving_ccw || blend_running; }
  bool any_error() const noexcept {
    return cfg_error || command_error || invalid_profile || input_error || home_invalid ||
           position_invalid;
  }
  // The error bit of list `list` (docs/error-reasons.md: 1 CFG ... 6 PI) is set.
  bool has_list(unsigned list) const noexcept {
    const bool bits[] = {false,       cfg_error,    command_error,   invalid_profile,
                         input_error, home_invalid, position_invalid};
    return list < 7 && bits[list];
  }
  // "configuration", "moving cw", "hold", "at home", "complete", "stopped", "idle".
  std::string state() const;
  // "Command Error, Invalid Profile" or "" (the manuals' names).
  std::string error_names() const;
};

// Every axis/channel of a module of `type` (its registry row's summarize).
std::vector<AxisSummary> summarize(ModuleType type, const ImageWords& in);

// A status word's bits, whichever module: each module's summary (tools/ctl_status_XXXX.cpp) fills
// one from its words' constants.
struct StatusBits {
  std::uint32_t cfg_mode, cw, ccw, hold, stopped, at_home, complete;
  std::uint32_t cfg, ce, ip, ie, hi, pi;
};
// The flags of one status word (blend_running and position are the module's to add).
AxisSummary summary_from_word(std::uint32_t w, const StatusBits& b);

// How a motion ended, for wait-idle and --wait: ok when it ended in Move Complete (At Home after
// a homing; a jog: stopped without an error), else a sentence with the reason.
struct MotionEnd {
  bool ok = false;
  std::string text;
};
// kAny (wait-idle): whatever ended, Move Complete or At Home is a success.
enum class Motion : std::uint8_t { kMove, kHome, kJog, kAny };
MotionEnd judge_end(const AxisSummary& s, Motion kind, const stepmod_reason_t& reason);

// The module's reason as printed after an error: "3601-CE-05: Vp 500 is below Vs 1000", or
// "" when none was recorded.
inline std::string reason_text(const stepmod_reason_t& r) {
  return r.seq == 0 ? std::string() : std::string(r.text);
}

}  // namespace stepmod::tools::ctl

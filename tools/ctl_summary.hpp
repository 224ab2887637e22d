#pragma once
// One axis/channel of any module in a few words (stepmodctl status --brief / --json, wait-idle
// and --wait): its state, position, error bits and the module's reason (docs/interface.md 3.4).
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <tuple>
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
  // The same names one by one (status --json).
  std::vector<std::string> error_list() const;
};

// Every axis/channel of a module of `type` (its registry row's summarize).
std::vector<AxisSummary> summarize(ModuleType type, const ImageWords& in);

// A status word's bit that shows a flag of the summary.
struct SummaryBit {
  std::uint32_t mask = 0;  // 0: a bit of the table that shows no flag of the summary
  bool AxisSummary::*flag = nullptr;
};

// The bits of a module's status word (tools/ctl_status_XXXX.cpp) that show a summary flag, found
// by name in its manual's table: the manuals name them alike but for the 3602's "CW Motion",
// "CCW Motion" and "Axis Stopped".
template <typename Table>
consteval auto summary_bits_of(const Table& t) {
  using S = AxisSummary;
  std::array<SummaryBit, std::tuple_size_v<Table>> out{};
  // Gives `flag` to the table's bit of that name (or of the 3602's name).
  const auto name = [&t, &out](bool S::*flag, std::string_view n, std::string_view n_3602 = {}) {
    for (std::size_t i = 0; i < out.size(); ++i) {
      if (t[i].name == n || t[i].name == n_3602) {
        out[i] = {((1u << t[i].width) - 1u) << t[i].bit, flag};
      }
    }
  };
  name(&S::configuration_mode, "Configuration Mode");
  name(&S::moving_cw, "Moving CW", "CW Motion");
  name(&S::moving_ccw, "Moving CCW", "CCW Motion");
  name(&S::blend_running, "Blend Move Running");
  name(&S::hold, "Hold State");
  name(&S::stopped, "Stopped", "Axis Stopped");
  name(&S::at_home, "At Home");
  name(&S::move_complete, "Move Complete");
  name(&S::cfg_error, "Configuration Error");
  name(&S::command_error, "Command Error");
  name(&S::invalid_profile, "Invalid Profile");
  name(&S::input_error, "Input Error");
  name(&S::home_invalid, "Home Invalid");
  name(&S::position_invalid, "Position Invalid");
  return out;
}

// The flags of one status word (position, and a blend bit in another word, are the module's).
AxisSummary summary_from_word(std::uint32_t w, std::span<const SummaryBit> bits);

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

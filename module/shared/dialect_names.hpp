#pragma once
// What the three dialects translate alike, found by name in each manual's word tables
// (words/words_3601.hpp, _3602, _3202) at compile time: the command bits and the commands they
// ask for, the status bits and the shared axis' flags they show, the acceleration-shape bits.
// The manuals give a bit the same name where it means the same; where the 3602 renames one
// ("Jog CW" for "Manual Move CW", "CW Motion" for "Moving CW") both names are listed. A bit of a
// module's table that no row here names is that dialect's own business.
#include <array>
#include <cstddef>
#include <string_view>

#include "core/bit_table.hpp"
#include "module/axis/axis_command.hpp"
#include "module/axis/axis_status.hpp"
#include "planner/ramp.hpp"

namespace stepmod::module::shared {

namespace names {
using enum axis::CommandKind;
struct Command {
  std::string_view name;
  axis::CommandKind kind;
};
// The command bits (3601/3202 manual ch. 5, 3602 manual ch. 9 table 9.3).
inline constexpr Command kCommands[] = {{"Absolute Move", kAbsoluteMove},
                                        {"Relative Move", kRelativeMove},
                                        {"Hold Move", kHold},
                                        {"Resume Move", kResume},
                                        {"Immediate Stop", kImmediateStop},
                                        {"Find Home CW", kFindHomeCw},
                                        {"Find Home CCW", kFindHomeCcw},
                                        {"Manual Move CW", kManualCw},
                                        {"Manual Move CCW", kManualCcw},
                                        {"Jog CW (Registration CW)", kManualCw},
                                        {"Jog CCW (Registration CCW)", kManualCcw},
                                        {"Preset Position", kPresetPosition},
                                        {"Preset Encoder", kPresetEncoder},
                                        {"Reset Errors", kResetErrors},
                                        {"Run Blend Move CW", kRunBlendCw},
                                        {"Run Blend Move CCW", kRunBlendCcw}};

using axis::AxisStatus;
struct Status {
  std::string_view name;
  bool AxisStatus::*flag;
};
// The status bits that show a flag of the shared axis (3601/3202 manual ch. 6, 3602 manual ch. 9).
inline constexpr Status kStatus[] = {
    {"Moving CW", &AxisStatus::moving_cw},
    {"CW Motion", &AxisStatus::moving_cw},
    {"Moving CCW", &AxisStatus::moving_ccw},
    {"CCW Motion", &AxisStatus::moving_ccw},
    {"Hold State", &AxisStatus::hold},
    {"Stopped", &AxisStatus::stopped},
    {"Axis Stopped", &AxisStatus::stopped},
    {"At Home", &AxisStatus::at_home},
    {"Accelerating", &AxisStatus::accelerating},
    {"Decelerating", &AxisStatus::decelerating},
    {"Move Complete", &AxisStatus::move_complete},
    {"Home Invalid", &AxisStatus::home_invalid},
    {"Invalid Profile", &AxisStatus::invalid_profile},
    {"Position Invalid", &AxisStatus::position_invalid},
    {"Input Error", &AxisStatus::input_error},
    {"Command Error", &AxisStatus::command_error},
    {"Configuration Error", &AxisStatus::configuration_error},
    {"Encoder Follower Mode", &AxisStatus::follower_mode},
    {"Blend Move Running", &AxisStatus::blend_running},
    {"Blend Block Acknowledge", &AxisStatus::blend_acknowledge},
    {"Min. Registration Distance Set", &AxisStatus::min_registration_set},
    {"Backplane Home Proximity Echo", &AxisStatus::proximity_echo}};
}  // namespace names

template <typename Word>
struct CommandBit {
  Word bit = 0;  // 0: a bit of the table that asks for no command (never matches)
  axis::CommandKind kind = axis::CommandKind::kUndefined;
};

// A command word's bits and the commands they ask for, from the manual's table `t`; the last row
// is `reserved`, bits that are a command the manual does not define (A33: Command Error).
template <typename Word, std::size_t N>
consteval std::array<CommandBit<Word>, N + 1> command_bits_of(const std::array<NamedBit, N>& t,
                                                              Word reserved) {
  std::array<CommandBit<Word>, N + 1> out{};
  for (std::size_t i = 0; i < N; ++i) {
    for (const names::Command& c : names::kCommands) {
      if (c.name == t[i].name) out[i] = {mask_of<Word>(t, c.name), c.kind};
    }
  }
  out[N] = {reserved, axis::CommandKind::kUndefined};
  return out;
}

template <typename Word, std::size_t N>
void read_commands(const std::array<CommandBit<Word>, N>& bits, Word word,
                   axis::CommandSet& commands) noexcept {
  for (const CommandBit<Word>& b : bits) {
    if (word & b.bit) commands.set(b.kind);
  }
}

template <typename Word>
struct StatusBit {
  Word bit = 0;  // 0: a bit of the table that shows no flag of the axis
  bool axis::AxisStatus::*flag = nullptr;
};

// A status word's bits that show a flag of the shared axis, from the manual's table `t`.
template <typename Word, std::size_t N>
consteval std::array<StatusBit<Word>, N> status_bits_of(const std::array<NamedBit, N>& t) {
  std::array<StatusBit<Word>, N> out{};
  for (std::size_t i = 0; i < N; ++i) {
    for (const names::Status& s : names::kStatus) {
      if (s.name == t[i].name) out[i] = {mask_of<Word>(t, s.name), s.flag};
    }
  }
  return out;
}

// The bits of `bits` whose flag is set in `s`.
template <typename Word, std::size_t N>
Word status_flags(const std::array<StatusBit<Word>, N>& bits, const axis::AxisStatus& s) noexcept {
  Word w = 0;
  for (const StatusBit<Word>& b : bits) {
    if (b.flag != nullptr && s.*b.flag) w = static_cast<Word>(w | b.bit);
  }
  return w;
}

// The acceleration-shape bits of a command word (all three manuals: the S-curve bit, then the
// trapezoidal bit; the trapezoidal bit alone is still constant).
template <typename Word>
struct ShapeBits {
  Word s_curve;
  Word trapezoidal;
};
template <typename Word, typename Table>
consteval ShapeBits<Word> shape_bits_of(const Table& t) {
  return {mask_of<Word>(t, "S-Curve Acceleration (0 = constant)"),
          mask_of<Word>(t, "Trapezoidal S-Curve (0 = triangular)")};
}
template <typename Word>
constexpr planner::AccelShape accel_shape(const ShapeBits<Word>& b, Word word) noexcept {
  if (!(word & b.s_curve)) return planner::AccelShape::kConstant;
  return (word & b.trapezoidal) ? planner::AccelShape::kTrapezoidalS
                                : planner::AccelShape::kTriangularS;
}

}  // namespace stepmod::module::shared

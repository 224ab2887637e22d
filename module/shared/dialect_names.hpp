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
#include "core/module_shape.hpp"
#include "module/axis/axis_command.hpp"
#include "module/axis/axis_status.hpp"
#include "planner/ramp.hpp"

namespace stepmod::module::shared {

namespace names {
using enum axis::CommandKind;
// A command bit's name in the manuals and the command it is.
struct CommandName {
  std::string_view name;
  axis::CommandKind kind;
};
// The command bits (3601/3202 manual ch. 5, 3602 manual ch. 9 table 9.3).
inline constexpr CommandName kCommands[] = {{"Absolute Move", kAbsoluteMove},
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

// A flag and the name its bit has in the manuals (and the 3602's name where it differs).
template <typename Struct>
struct Flag {
  bool Struct::*flag;
  std::string_view name;
  std::string_view name_3602 = {};
};
using axis::AxisCommand;
// The command bits that set an option of the decoded command (3601/3202 manual ch. 5, 3602 manual
// ch. 9 table 9.4).
inline constexpr Flag<AxisCommand> kCommandFlags[] = {
    {&AxisCommand::encoder_move, "Encoder Move"},
    {&AxisCommand::follower, "Encoder Follower"},
    {&AxisCommand::blend_program, "Program Blend Move"},
    {&AxisCommand::blend_transmit, "Blend Move Data Transmit"},
    {&AxisCommand::store_min_registration, "Store Minimum Registration Distance",
     "Program Minimum Registration Distance"},
    {&AxisCommand::backplane_proximity, "Backplane Home Proximity"}};

using axis::AxisStatus;
// The status bits that show a flag of the shared axis (3601/3202 manual ch. 6, 3602 manual ch. 9).
inline constexpr Flag<AxisStatus> kStatus[] = {
    {&AxisStatus::moving_cw, "Moving CW", "CW Motion"},
    {&AxisStatus::moving_ccw, "Moving CCW", "CCW Motion"},
    {&AxisStatus::hold, "Hold State"},
    {&AxisStatus::stopped, "Stopped", "Axis Stopped"},
    {&AxisStatus::at_home, "At Home"},
    {&AxisStatus::accelerating, "Accelerating"},
    {&AxisStatus::decelerating, "Decelerating"},
    {&AxisStatus::move_complete, "Move Complete"},
    {&AxisStatus::home_invalid, "Home Invalid"},
    {&AxisStatus::invalid_profile, "Invalid Profile"},
    {&AxisStatus::position_invalid, "Position Invalid"},
    {&AxisStatus::input_error, "Input Error"},
    {&AxisStatus::command_error, "Command Error"},
    {&AxisStatus::configuration_error, "Configuration Error"},
    {&AxisStatus::follower_mode, "Encoder Follower Mode"},
    {&AxisStatus::blend_running, "Blend Move Running"},
    {&AxisStatus::blend_acknowledge, "Blend Block Acknowledge"},
    {&AxisStatus::min_registration_set, "Min. Registration Distance Set"},
    {&AxisStatus::proximity_echo, "Backplane Home Proximity Echo"}};
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
    for (const names::CommandName& c : names::kCommands) {
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

template <typename Word, typename Struct>
struct FlagBit {
  Word bit = 0;  // 0: a bit of the table that is no flag of `Struct`
  bool Struct::*flag = nullptr;
};

// A word's bits that stand for a flag of `Struct`, from the manual's table `t` and one of the name
// tables above.
template <typename Word, typename Struct, std::size_t N, std::size_t M>
consteval std::array<FlagBit<Word, Struct>, N> flag_bits_of(const std::array<NamedBit, N>& t,
                                                            const names::Flag<Struct> (&n)[M]) {
  std::array<FlagBit<Word, Struct>, N> out{};
  for (std::size_t i = 0; i < N; ++i) {
    for (const names::Flag<Struct>& f : n) {
      if (f.name == t[i].name || f.name_3602 == t[i].name)
        out[i] = {mask_of<Word>(t, t[i].name), f.flag};
    }
  }
  return out;
}
template <typename Word, std::size_t N>
consteval auto status_bits_of(const std::array<NamedBit, N>& t) {
  return flag_bits_of<Word>(t, names::kStatus);
}
template <typename Word, std::size_t N>
consteval auto option_bits_of(const std::array<NamedBit, N>& t) {
  return flag_bits_of<Word>(t, names::kCommandFlags);
}

// The bits of `bits` whose flag is set in `s` (status words).
template <typename Word, typename Struct, std::size_t N>
Word flags_to_word(const std::array<FlagBit<Word, Struct>, N>& bits, const Struct& s) noexcept {
  Word w = 0;
  for (const FlagBit<Word, Struct>& b : bits) {
    if (b.flag != nullptr && s.*b.flag) w = static_cast<Word>(w | b.bit);
  }
  return w;
}

// Sets the flags of `s` whose bit `word` has (command options; a flag two bits name is set by
// either).
template <typename Word, typename Struct, std::size_t N>
void word_to_flags(const std::array<FlagBit<Word, Struct>, N>& bits, Word word,
                   Struct& s) noexcept {
  for (const FlagBit<Word, Struct>& b : bits) {
    if (b.flag != nullptr && (word & b.bit) != 0) s.*b.flag = true;
  }
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

// Everything the shared names find in a dialect's command words: the command bits (with the
// reserved ones last), the mode bit, and in the options word (the 3601/3602 LSW; the 3202's one
// DINT holds both) the acceleration shape and the command's option flags.
template <typename Word, std::size_t NC, std::size_t NO>
struct CommandWords {
  std::array<CommandBit<Word>, NC + 1> commands;
  Word config_mode;
  ShapeBits<Word> shape;
  std::array<FlagBit<Word, axis::AxisCommand>, NO> options;
};
template <typename Word, std::size_t NC, std::size_t NO>
consteval CommandWords<Word, NC, NO> command_words_of(const std::array<NamedBit, NC>& commands,
                                                      Word reserved,
                                                      const std::array<NamedBit, NO>& options) {
  return {command_bits_of(commands, reserved), mask_of<Word>(commands, "Configuration Mode"),
          shape_bits_of<Word>(options), option_bits_of<Word>(options)};
}

// A decoded command with what `t` names read from its words; the rest is the dialect's.
template <typename Word, std::size_t NC, std::size_t NO>
axis::AxisCommand decode_command_bits(const CommandWords<Word, NC, NO>& t, Word command_word,
                                      Word option_word) noexcept {
  axis::AxisCommand c;
  c.configuration_mode = (command_word & t.config_mode) != 0;
  read_commands(t.commands, command_word, c.commands);
  c.shape = accel_shape(t.shape, option_word);
  word_to_flags(t.options, option_word, c);
  return c;
}

// The same from a 16-bit module's output image (3601, 3602): the command MSW at word `msw` and
// its options LSW right after it, as both manuals place them.
template <std::size_t NC, std::size_t NO>
axis::AxisCommand decode_command_words16(const CommandWords<std::uint16_t, NC, NO>& t,
                                         const ImageWords& out, unsigned msw) noexcept {
  return decode_command_bits(t, static_cast<std::uint16_t>(out.w[msw]),
                             static_cast<std::uint16_t>(out.w[msw + 1]));
}

}  // namespace stepmod::module::shared

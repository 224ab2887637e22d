#pragma once
// The decoded command image of one axis/channel for one scan: which commands are asked for, the
// level bits, and the parameters as numbers in the shared code's units (steps, steps/s,
// steps/s^2). A dialect (module/m3601/...) builds it from its command words, word-level rules
// included; the shared axis code finds the 0->1 edges itself, on command kinds (3601 Ch.4 general
// note 3).
#include <array>
#include <bitset>
#include <cstdint>
#include <optional>

#include "module/axis/error_reason.hpp"
#include "planner/motion_request.hpp"

namespace stepmod::module::axis {

// Every command a module's command word can ask for. kUndefined stands for a command bit the
// manual does not define (A33): set with or without a command it is a Command Error.
enum class CommandKind : std::uint8_t {
  kAbsoluteMove,
  kRelativeMove,
  kHold,
  kResume,
  kImmediateStop,
  kFindHomeCw,
  kFindHomeCcw,
  kManualCw,   // level: runs while held; with the follower flag, "same sense"
  kManualCcw,  // level; with the follower flag, "reverse sense"
  kPresetPosition,
  kPresetEncoder,
  kResetErrors,
  kRunBlendCw,
  kRunBlendCcw,
  kUndefined,
  kCount
};

// A set of command kinds (the command bits set in one scan, or the ones that rose).
class CommandSet {
 public:
  constexpr CommandSet() = default;
  void set(CommandKind k) noexcept { bits_.set(index(k)); }
  bool has(CommandKind k) const noexcept { return bits_.test(index(k)); }
  bool empty() const noexcept { return bits_.none(); }
  std::size_t count() const noexcept { return bits_.count(); }
  // The kinds set here and not in `before`: this scan's 0->1 edges.
  CommandSet rising_since(const CommandSet& before) const noexcept {
    CommandSet r;
    r.bits_ = bits_ & ~before.bits_;
    return r;
  }
  // Set algebra, for commands a coordinator keeps from an axis (module/m3602/interpolated_move).
  CommandSet minus(const CommandSet& o) const noexcept {
    CommandSet r;
    r.bits_ = bits_ & ~o.bits_;
    return r;
  }
  CommandSet common(const CommandSet& o) const noexcept {
    CommandSet r;
    r.bits_ = bits_ & o.bits_;
    return r;
  }
  CommandSet with(const CommandSet& o) const noexcept {
    CommandSet r;
    r.bits_ = bits_ | o.bits_;
    return r;
  }
  CommandSet without(CommandKind a, CommandKind b) const noexcept {
    CommandSet r = *this;
    r.bits_.reset(index(a));
    r.bits_.reset(index(b));
    return r;
  }
  // The one kind of a set of exactly one.
  std::optional<CommandKind> single() const noexcept {
    if (count() != 1) return std::nullopt;
    for (std::size_t i = 0; i < bits_.size(); ++i) {
      if (bits_.test(i)) return static_cast<CommandKind>(i);
    }
    return std::nullopt;
  }
  bool operator==(const CommandSet&) const = default;

 private:
  static constexpr std::size_t index(CommandKind k) noexcept { return static_cast<std::size_t>(k); }
  std::bitset<static_cast<std::size_t>(CommandKind::kCount)> bits_;
};

// The first block of a blend programming cycle (3601 Ch.5 "Blend Move Programming").
struct BlendFirstBlock {
  std::int32_t segments = 0;                       // declared count (valid: 2..16)
  std::array<planner::AccelShape, 16> shapes{};    // acceleration type of segment 1..16
  std::optional<planner::AccelShape> final_shape;  // nullopt: a type the manual forbids
  std::int64_t final_decel = 0;                    // steps/s^2; 0 = none given (CE-24)
  bool unused_words_zero = true;                   // the words the block leaves empty are 0
};

// A segment block: length, speed, the rate that reaches the speed (3601 Ch.5 "Blend Move
// Programming").
struct BlendSegmentBlock {
  std::optional<std::int32_t> length;  // nullopt: not encodable
  std::optional<std::int32_t> speed;   // steps/s
  std::int64_t rate = 0;               // steps/s^2
  bool unused_words_zero = true;
};

struct AxisCommand {
  bool configuration_mode = false;  // the mode bit: configuration requested
  CommandSet commands;              // command bits set in this scan (levels)
  // A word-level rule of the dialect is broken for the one command set (words that must be 0, a
  // command LSW that must be 0, ...), or for the minimum-registration store: Command Error.
  bool words_invalid = false;
  // The checklist item of that rule when it is not the general one (items::kWordsNotZero): the
  // 3602's single-axis command with the interpolation bits is 3602-CE-03.
  const Item* words_item = nullptr;
  // The module's reserved command words are not 0 (3202-CE-05 / IP-03, and HI-04 for a homing
  // command): CE + IP (+ HI). Modules without reserved command words leave it false.
  bool reserved_words_nonzero = false;

  // Parameters, decoded (nullopt: the words hold no valid number in the module's encoding).
  std::optional<std::int32_t> target;  // target / preset value / registration count / distance
  std::optional<std::int32_t> speed;   // programmed speed, steps/s
  std::int64_t accel = 0;              // steps/s^2 (0: the words were 0)
  std::int64_t decel = 0;
  planner::AccelShape shape = planner::AccelShape::kConstant;  // S-curve selection

  // Level and modifier bits.
  bool encoder_move = false;            // absolute/relative moves count encoder counts
  bool follower = false;                // encoder follower mode
  bool blend_program = false;           // blend programming cycle (level)
  bool blend_transmit = false;          // one block offered (its 0->1 edge reads it)
  bool store_min_registration = false;  // store the minimum registration distance (edge)
  bool backplane_proximity = false;     // proximity bit for homing (level)

  // Encoder follower ratio (multiplier / divisor, plain integers).
  std::int32_t ratio_multiplier = 0;
  std::int32_t ratio_divisor = 0;

  // The image read as blend programming blocks (looked at on a transmit edge only).
  BlendFirstBlock blend_first;
  BlendSegmentBlock blend_segment;

  bool s_curve() const noexcept { return shape != planner::AccelShape::kConstant; }
};

}  // namespace stepmod::module::axis

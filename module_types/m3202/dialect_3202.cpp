// The 3202's command and status DINTs <-> the shared axis' decoded command and status (3202
// manual Ch.5 "Command Word Layout", Ch.6 "Status Word Layout").
#include "module_types/m3202/dialect_3202.hpp"
#include "module_types/m3202/rules_3202.hpp"

#include "module/axis/rules.hpp"
#include "module_types/m3202/words_3202.hpp"

namespace stepmod::module::m3202 {
using namespace words::m3202;  // this module's words: module_types/m3202/words_3202.hpp

namespace {

using axis::CommandKind;

// A31: the 3202's accel/decel DINTs are steps/s^2 already (unit 1).
constexpr std::int64_t kAccelUnit = kRules3202.accel_word_unit;

struct CommandBit {
  std::uint32_t bit;
  CommandKind kind;
};
constexpr CommandBit kCommandKinds[] = {
    {cmd_bit::kAbsoluteMove, CommandKind::kAbsoluteMove},
    {cmd_bit::kRelativeMove, CommandKind::kRelativeMove},
    {cmd_bit::kHold, CommandKind::kHold},
    {cmd_bit::kResume, CommandKind::kResume},
    {cmd_bit::kImmediateStop, CommandKind::kImmediateStop},
    {cmd_bit::kFindHomeCw, CommandKind::kFindHomeCw},
    {cmd_bit::kFindHomeCcw, CommandKind::kFindHomeCcw},
    {cmd_bit::kManualCw, CommandKind::kManualCw},
    {cmd_bit::kManualCcw, CommandKind::kManualCcw},
    {cmd_bit::kPresetPosition, CommandKind::kPresetPosition},
    {cmd_bit::kPresetEncoder, CommandKind::kPresetEncoder},
    {cmd_bit::kResetErrors, CommandKind::kResetErrors},
    {cmd_bit::kRunBlendCw, CommandKind::kRunBlendCw},
    {cmd_bit::kRunBlendCcw, CommandKind::kRunBlendCcw},
};

// Command word bits 16/17: constant, triangular S or trapezoidal S (17 ignored without 16).
planner::AccelShape shape_from_word(std::uint32_t w) noexcept {
  if (!(w & cmd_bit::kSCurve)) return planner::AccelShape::kConstant;
  return (w & cmd_bit::kTrapezoidalS) ? planner::AccelShape::kTrapezoidalS
                                      : planner::AccelShape::kTriangularS;
}

// The per-command "must be 0" rules of the command table (3202 manual ch. 5: speed/accel/decel 0
// for both presets, 3202-CE-09; target/speed/accel/decel 0 for Run Blend, 3202-CE-18).
bool word_rules_broken(const ImageWords& out, unsigned b, const axis::AxisCommand& c) noexcept {
  const auto only = c.commands.single();
  if (!only) return false;
  const bool rates_zero = out.w[b + out_word::kSpeed] == 0 && out.w[b + out_word::kAccel] == 0 &&
                          out.w[b + out_word::kDecel] == 0;
  switch (*only) {
    case CommandKind::kPresetPosition:
    case CommandKind::kPresetEncoder:
      return !rates_zero;
    case CommandKind::kRunBlendCw:
    case CommandKind::kRunBlendCcw:
      return !rates_zero || out.w[b + out_word::kTarget] != 0;
    default:
      return false;
  }
}

}  // namespace

axis::AxisCommand command_from_words(const ImageWords& out, unsigned channel) noexcept {
  const unsigned b = channel_base(channel);
  const auto w = static_cast<std::uint32_t>(out.w[b + out_word::kCommand]);
  axis::AxisCommand c;
  c.configuration_mode = (w & cmd_bit::kConfigMode) != 0;
  for (const CommandBit& cb : kCommandKinds) {
    if (w & cb.bit) c.commands.set(cb.kind);
  }
  // 3202-CE-24, A33: a reserved command bit counts as an extra, undefined command.
  if (w & cmd_bit::kReserved) c.commands.set(CommandKind::kUndefined);
  // Native DINTs (3202 manual ch. 5). A negative speed is no valid speed.
  c.target = out.w[b + out_word::kTarget];
  const std::int32_t speed = out.w[b + out_word::kSpeed];
  if (speed >= 0) c.speed = speed;
  c.accel = static_cast<std::int64_t>(out.w[b + out_word::kAccel]) * kAccelUnit;
  c.decel = static_cast<std::int64_t>(out.w[b + out_word::kDecel]) * kAccelUnit;
  c.shape = shape_from_word(w);
  c.encoder_move = (w & cmd_bit::kEncoderMove) != 0;
  c.backplane_proximity = (w & cmd_bit::kBackplaneProximity) != 0;
  // 3202-CE-05 / IP-03 / HI-04: DINTs b+5..b+7 are reserved and must be 0.
  for (unsigned i = out_word::kFirstReserved; i < kWordsPerChannel; ++i) {
    if (out.w[b + i] != 0) c.reserved_words_nonzero = true;
  }
  // The 3202 has no follower, no word-block blend programming and no minimum registration
  // distance (3202 manual ch. 5): those flags stay false.
  c.words_invalid = word_rules_broken(out, b, c);
  return c;
}

void status_to_words(const axis::AxisStatus& s, bool disabled, unsigned channel,
                     ImageWords& in) noexcept {
  std::uint32_t w = status_bit::kModuleOk;  // 3202-MOK-01
  if (s.moving_cw) w |= status_bit::kMovingCw;
  if (s.moving_ccw) w |= status_bit::kMovingCcw;
  if (s.hold) w |= status_bit::kHoldState;
  if (s.stopped) w |= status_bit::kStopped;
  if (s.at_home) w |= status_bit::kAtHome;
  if (s.accelerating) w |= status_bit::kAccelerating;
  if (s.decelerating) w |= status_bit::kDecelerating;
  if (s.move_complete) w |= status_bit::kMoveComplete;
  if (s.blend_running) w |= status_bit::kBlendRunning;
  if (s.position_invalid) w |= status_bit::kPositionInvalid;
  if (s.input_error) w |= status_bit::kInputError;
  if (s.command_error) w |= status_bit::kCommandError;
  // Status bit 13 (3202 manual ch. 6): never set while the channel is disabled.
  if (s.configuration_error && !disabled) w |= status_bit::kConfigurationError;
  if (s.home_invalid) w |= status_bit::kHomeInvalid;
  if (s.invalid_profile) w |= status_bit::kInvalidProfile;
  w |= static_cast<std::uint32_t>(s.inputs_active & 0x3Fu) << status_bit::kInputShift;
  if (disabled) w |= status_bit::kChannelDisabled;  // 3202-DIS-01
  if (s.proximity_echo) w |= status_bit::kProximityEcho;

  const unsigned b = channel_base(channel);
  for (unsigned i = 0; i < kWordsPerChannel; ++i) in.w[b + i] = 0;
  in.w[b + in_word::kStatus] = static_cast<std::int32_t>(w);
  // Native DINTs (3202 manual ch. 5, 6): the registers use all 32 bits and roll over.
  in.w[b + in_word::kPosition] = static_cast<std::int32_t>(static_cast<std::uint32_t>(s.position));
  in.w[b + in_word::kEncoder] = static_cast<std::int32_t>(static_cast<std::uint32_t>(s.encoder));
  in.w[b + in_word::kCapture] = static_cast<std::int32_t>(static_cast<std::uint32_t>(s.capture));
}

void configuration_image_to_words(const ConfigMirror& mirror, bool configuration_error,
                                  bool disabled, unsigned channel, ImageWords& in) noexcept {
  constexpr std::uint32_t kModuleBits = status_bit::kConfigurationError |
                                        status_bit::kChannelDisabled | status_bit::kModuleOk |
                                        status_bit::kConfigMode;
  std::uint32_t w0 = mirror.bits & ~kModuleBits;
  // Status bit 13 (3202 manual ch. 6): never set while the channel is disabled.
  if (configuration_error && !disabled) w0 |= status_bit::kConfigurationError;
  if (disabled) w0 |= status_bit::kChannelDisabled;
  w0 |= status_bit::kModuleOk | status_bit::kConfigMode;
  const unsigned b = channel_base(channel);
  for (unsigned i = 0; i < kWordsPerChannel; ++i) in.w[b + i] = 0;
  in.w[b + 0] = static_cast<std::int32_t>(w0);
  in.w[b + 1] = mirror.starting_speed;
  in.w[b + 3] = static_cast<std::int32_t>((kFirmwareMajor << 16) | kFirmwareMinor);
}

}  // namespace stepmod::module::m3202

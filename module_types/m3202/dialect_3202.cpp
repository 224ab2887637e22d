// The 3202's command and status DINTs <-> the shared axis' decoded command and status (3202
// manual Ch.5 "Command Word Layout", Ch.6 "Status Word Layout").
#include "module_types/m3202/dialect_3202.hpp"
#include "module_types/m3202/rules_3202.hpp"

#include "module/axis/rules.hpp"
#include "module/shared/dialect_names.hpp"
#include "module_types/m3202/words_3202.hpp"

namespace stepmod::module::m3202 {
using namespace words::m3202;  // this module's words: module_types/m3202/words_3202.hpp

namespace {

using axis::CommandKind;

// A31: the 3202's accel/decel DINTs are steps/s^2 already (unit 1).
constexpr std::int64_t kAccelUnit = kRules3202.accel_word_unit;

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

// 3202-CE-24, A33: a reserved command bit counts as an extra, undefined command (the last row).
constexpr auto kCommandWords =
    shared::command_words_of(kCommandBits, cmd_bit::kReserved, kCommandBits);
}  // namespace

axis::AxisCommand command_from_words(const ImageWords& out, unsigned channel) noexcept {
  const unsigned b = channel_base(channel);
  const auto w = static_cast<std::uint32_t>(out.w[b + out_word::kCommand]);
  axis::AxisCommand c = shared::decode_command_bits(kCommandWords, w, w);
  // Native DINTs (3202 manual ch. 5). A negative speed is no valid speed.
  c.target = out.w[b + out_word::kTarget];
  const std::int32_t speed = out.w[b + out_word::kSpeed];
  if (speed >= 0) c.speed = speed;
  c.accel = static_cast<std::int64_t>(out.w[b + out_word::kAccel]) * kAccelUnit;
  c.decel = static_cast<std::int64_t>(out.w[b + out_word::kDecel]) * kAccelUnit;
  // 3202-CE-05 / IP-03 / HI-04: DINTs b+5..b+7 are reserved and must be 0.
  for (unsigned i = out_word::kFirstReserved; i < kWordsPerChannel; ++i) {
    if (out.w[b + i] != 0) c.reserved_words_nonzero = true;
  }
  // The 3202 has no follower, no word-block blend programming and no minimum registration
  // distance (3202 manual ch. 5): those flags stay false.
  c.words_invalid = word_rules_broken(out, b, c);
  return c;
}

namespace {
// The status bits that show the shared axis' flags, by their names in the manual.
constexpr auto kStatusFlags = shared::status_bits_of<std::uint32_t>(kStatusBits);
}  // namespace

void status_to_words(const axis::AxisStatus& s, bool disabled, unsigned channel,
                     ImageWords& in) noexcept {
  std::uint32_t w = status_bit::kModuleOk | shared::flags_to_word(kStatusFlags, s);  // 3202-MOK-01
  // Status bit 13 (3202 manual ch. 6): never set while the channel is disabled.
  if (disabled) w &= ~status_bit::kConfigurationError;
  w |= static_cast<std::uint32_t>(s.inputs_active & 0x3Fu) << status_bit::kInputShift;
  if (disabled) w |= status_bit::kChannelDisabled;  // 3202-DIS-01

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

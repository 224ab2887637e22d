// The 3601's command and status words <-> the shared axis' decoded command and status (3601
// manual Ch.5 "Command Mode Output Data", Ch.6 "Input Data").
#include "module_types/m3601/dialect_3601.hpp"
#include "module_types/m3601/rules_3601.hpp"

#include "module/axis/rules.hpp"
#include "module/blend_types_16bit.hpp"
#include "module/shared/dialect_names.hpp"
#include "module_types/m3601/words_3601.hpp"

namespace stepmod::module::m3601 {
using namespace words::m3601;  // this module's words: module_types/m3601/words_3601.hpp

namespace {

using axis::CommandKind;

// Accel/decel words are steps/ms/s; the shared code works in steps/s^2 (3601 manual ch. 5).
constexpr std::int64_t kAccelUnit = kRules3601.accel_word_unit;

std::int32_t word(const ImageWords& out, unsigned i) noexcept {
  return static_cast<std::int16_t>(out.w[i]);
}

// Whether output words first..last are all 0 (the "must be 0" rules of the command table).
bool words_zero(const ImageWords& out, unsigned first, unsigned last) noexcept {
  for (unsigned w = first; w <= last; ++w) {
    if (out.w[w] != 0) return false;
  }
  return true;
}

// First blend block (3601 manual ch. 5): word 2 the segment count, words 4 / 3 the
// acceleration-type pairs of segments 1..8 / 9..16 (two bits each, segment 1 or 9 in bits 1:0),
// word 5 the final deceleration (type in bits 15-14, value in bits 13-0), words 6 and 7 zero.
constexpr unsigned kSegmentCountWord = 2;
constexpr unsigned kPairs9To16Word = 3;
constexpr unsigned kPairs1To8Word = 4;
constexpr unsigned kFinalDecelWord = 5;

axis::BlendFirstBlock blend_first_block(const ImageWords& out) noexcept {
  axis::BlendFirstBlock b;
  b.segments = word(out, kSegmentCountWord);
  decode_blend_types_16bit(out, kPairs1To8Word, kPairs9To16Word, kFinalDecelWord, b);
  const auto w5 = static_cast<std::uint16_t>(out.w[kFinalDecelWord]);
  b.final_decel = static_cast<std::int64_t>(w5 & 0x3FFF) * kAccelUnit;
  b.unused_words_zero = out.w[out_word::kAccel] == 0 && out.w[out_word::kDecel] == 0;
  return b;
}

// The word rules of the command table for the one command set, or for the minimum-registration
// store when none is (true = broken: Command Error).
bool word_rules_broken(const ImageWords& out, const axis::AxisCommand& c) noexcept {
  const auto lsw = static_cast<std::uint16_t>(out.w[out_word::kLsw]);
  const auto only = c.commands.single();
  if (!only) {
    // Store minimum registration distance: word 1 exactly bit 10 and words 4..7 zero.
    return c.commands.empty() && c.store_min_registration &&
           (lsw != cmd_lsw::kStoreMinRegistration ||
            !words_zero(out, out_word::kSpeedMsw, out_word::kDecel));
  }
  switch (*only) {
    case CommandKind::kPresetPosition:
    case CommandKind::kPresetEncoder:
      // 3601-CE-09: speed, accel and decel words 0; 3601-CE-15: the command LSW 0.
      return !words_zero(out, out_word::kSpeedMsw, out_word::kDecel) || lsw != 0;
    case CommandKind::kResetErrors:
      return lsw != 0;  // 3601-CE-15
    case CommandKind::kRunBlendCw:
    case CommandKind::kRunBlendCcw:
      // 3601-CE-21: target, speed, accel and decel words 0; 3601-CE-15: the command LSW 0.
      return !words_zero(out, out_word::kTargetMsw, out_word::kDecel) || lsw != 0;
    default:
      return false;
  }
}

// Command MSW bits 0..14 and the command each one asks for (3601 manual ch. 5). Bit 14 is reserved:
// A33, set with or without a command it is a Command Error.
constexpr auto kCommandWords =
    shared::command_words_of(kCommandMswBits, cmd_msw::kReserved14, kCommandLswBits);
}  // namespace

axis::AxisCommand command_from_words(const ImageWords& out) noexcept {
  axis::AxisCommand c = shared::decode_command_words16(kCommandWords, out, out_word::kMsw);
  // Words 2-3: target / preset value / registration count / distance / blend segment length
  // (decimal split, LSW -999..999, both words of one sign); words 4-5: speed (never negative).
  c.target = words::decode_3601(out.w[out_word::kTargetMsw], out.w[out_word::kTargetLsw]);
  c.speed = words::decode_3601_unsigned(out.w[out_word::kSpeedMsw], out.w[out_word::kSpeedLsw]);
  c.accel = word(out, out_word::kAccel) * kAccelUnit;
  c.decel = word(out, out_word::kDecel) * kAccelUnit;
  // Encoder follower: words 2 / 3 are the multiplier and divisor, plain integers.
  c.ratio_multiplier = word(out, out_word::kTargetMsw);
  c.ratio_divisor = word(out, out_word::kTargetLsw);
  c.blend_first = blend_first_block(out);
  c.blend_segment = blend_segment_16bit(c, out.w[out_word::kDecel] == 0);
  c.words_invalid = word_rules_broken(out, c);
  return c;
}

namespace {
// The status bits that show the shared axis' flags, by their names in the manual.
constexpr auto kMswFlags = shared::status_bits_of<std::uint16_t>(kStatusMswBits);
constexpr auto kLswFlags = shared::status_bits_of<std::uint16_t>(kStatusLswBits);
}  // namespace

void status_to_words(const axis::AxisStatus& s, ImageWords& in) noexcept {
  std::uint16_t msw = status_msw::kModuleOk;  // 3601-MOK-01: only a fatal fault clears it
  msw |= shared::flags_to_word(kMswFlags, s);

  // Status LSW bits 0..5: the inputs in InputLine order (capture, external, home, E-stop, CW
  // limit, CCW limit), 3601 manual ch. 6.
  constexpr std::uint16_t kInputBits = status_lsw::kCaptureActive | status_lsw::kExternalActive |
                                       status_lsw::kHomeActive | status_lsw::kEStopActive |
                                       status_lsw::kCwLimitActive | status_lsw::kCcwLimitActive;
  std::uint16_t lsw = s.inputs_active & kInputBits;
  lsw |= shared::flags_to_word(kLswFlags, s);

  in = ImageWords{};
  in.w[in_word::kStatusMsw] = static_cast<std::int16_t>(msw);
  in.w[in_word::kStatusLsw] = static_cast<std::int16_t>(lsw);
  const auto put = [&in](unsigned msw_index, std::int64_t value) {
    const auto split = words::encode_3601(value);
    in.w[msw_index] = split.msw;
    in.w[msw_index + 1] = split.lsw;
  };
  put(in_word::kPositionMsw, s.position);
  put(in_word::kEncoderMsw, s.encoder);
  put(in_word::kCaptureMsw, s.capture);
}

void configuration_image_to_words(const ConfigMirror& mirror, bool configuration_error,
                                  ImageWords& in) noexcept {
  in = ImageWords{};
  // Bits 0..12 mirror the configuration bits; 13..15 are the module's (CfgE, OK, mode).
  std::uint16_t w0 = mirror[0] & 0x1FFF;
  if (configuration_error) w0 |= status_msw::kConfigurationError;
  w0 |= status_msw::kModuleOk | status_msw::kConfigMode;
  in.w[0] = static_cast<std::int16_t>(w0);
  in.w[1] = static_cast<std::int16_t>(mirror[1]);
  in.w[2] = static_cast<std::int16_t>(mirror[2]);
  in.w[3] = static_cast<std::int16_t>(mirror[3]);
  in.w[in_word::kFirmwareMajor] = kFirmwareMajor;
  in.w[in_word::kFirmwareMinor] = kFirmwareMinor;
}

}  // namespace stepmod::module::m3601

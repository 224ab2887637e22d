// The 3602's command and status words of one axis <-> the shared axis' decoded command and status
// (3602 manual Ch.9 "Command Mode Data Format", Tables 9.2-9.22, 9.27).
#include "module_types/m3602/dialect_3602.hpp"
#include "module_types/m3602/rules_3602.hpp"

#include "core/lines.hpp"
#include "module/axis/rules.hpp"
#include "module/blend_types_16bit.hpp"
#include "module/shared/dialect_names.hpp"
#include "module_types/m3602/interpolated_items.hpp"
#include "module_types/m3602/words_3602.hpp"

namespace stepmod::module::m3602 {
using namespace words::m3602;  // this module's words: module_types/m3602/words_3602.hpp

namespace {

using axis::CommandKind;

// Accel/decel words are steps/ms/s; the shared code works in steps/s^2 (x 1000; 3602 manual Ch.9).
constexpr std::int64_t kAccelUnit = kRules3602.accel_word_unit;
// Command LSW bits 0/1 (3602 manual ch. 9 table 9.4): the acceleration shape.
constexpr auto kShapeBits = shared::shape_bits_of<std::uint16_t>(kCommandLswBits);

std::int32_t word(const ImageWords& out, unsigned i) noexcept {
  return static_cast<std::int16_t>(out.w[i]);
}
std::int32_t split(const ImageWords& out, unsigned msw_index) noexcept {
  return words::decode_3602(out.w[msw_index], out.w[msw_index + 1]);
}
bool words_zero(const ImageWords& out, unsigned first, unsigned last) noexcept {
  for (unsigned w = first; w <= last; ++w) {
    if (static_cast<std::int16_t>(out.w[w]) != 0) return false;
  }
  return true;
}

// First ("initial") blend block (3602 manual Table 9.21): word 2 the segment count, words 4 / 3
// the type pairs of segments 1..8 / 9..16, word 5 the final deceleration (type in bits 15-14,
// bits 13-11 zero, value in bits 10-0), words 6 and 7 zero.
constexpr unsigned kSegmentCountWord = 2;
constexpr unsigned kPairs9To16Word = 3;
constexpr unsigned kPairs1To8Word = 4;
constexpr unsigned kFinalDecelWord = 5;
constexpr std::uint16_t kFinalDecelValue = 0x07FF;
constexpr std::uint16_t kFinalDecelReserved = 0x3800;

axis::BlendFirstBlock blend_first_block(const ImageWords& out) noexcept {
  axis::BlendFirstBlock b;
  b.segments = word(out, kSegmentCountWord);
  decode_blend_types_16bit(out, kPairs1To8Word, kPairs9To16Word, kFinalDecelWord, b);
  const auto w5 = static_cast<std::uint16_t>(out.w[kFinalDecelWord]);
  b.final_decel = static_cast<std::int64_t>(w5 & kFinalDecelValue) * kAccelUnit;
  b.unused_words_zero = (w5 & kFinalDecelReserved) == 0 && words_zero(out, 6, 7);
  return b;
}

// Whether a type-pair word holds a pair of binary 10 among the declared segments (3602-IP-07).
bool has_invalid_pair(const ImageWords& out) noexcept {
  const std::int32_t n = word(out, kSegmentCountWord);
  for (std::int32_t s = 1; s <= 16 && s <= n; ++s) {
    const auto w = static_cast<std::uint16_t>(out.w[s <= 8 ? kPairs1To8Word : kPairs9To16Word]);
    if (((w >> (2 * ((s - 1) % 8))) & 0x3u) == 0b10u) return true;
  }
  return false;
}

// The LSW of Reset Errors, Run Blend and the minimum-registration store: nothing but the GPO bit
// besides the command's own (3602 manual Tables 9.5-9.20: "16#0000 or 16#0080 only").
bool lsw_only(std::uint16_t lsw, std::uint16_t allowed) noexcept {
  return (lsw & ~(allowed | cmd_lsw::kGpo)) == 0;
}

// The word rules of the command tables (3602 manual Tables 9.5-9.20) for the one command set, or
// for the minimum-registration store when none is (true = broken: 3602-CE-10 / CE-03).
bool word_rules_broken(const ImageWords& out, const axis::AxisCommand& c,
                       std::uint16_t lsw) noexcept {
  // 3602-CE-03: a single-axis command together with interpolation bits.
  if (!c.commands.empty() && (lsw & cmd_lsw::kInterpolation)) return true;
  const auto only = c.commands.single();
  if (!only) {
    // Set minimum registration distance: MSW 0, LSW 16#0004 / 16#0084, words 4..7 zero.
    return c.commands.empty() && c.store_min_registration &&
           (!lsw_only(lsw, cmd_lsw::kProgramMinRegistration) ||
            !words_zero(out, out_word::kSpeedMsw, out_word::kDecel));
  }
  switch (*only) {
    case CommandKind::kPresetPosition:
      return !words_zero(out, out_word::kSpeedMsw, out_word::kDecel);
    case CommandKind::kResetErrors:
    case CommandKind::kRunBlendCw:
    case CommandKind::kRunBlendCcw:
      return !lsw_only(lsw, 0) || !words_zero(out, out_word::kTargetMsw, out_word::kDecel);
    default:
      return false;
  }
}

// Interpolated block (3602 manual Tables 9.4, 9.23-9.26): the method from LSW bits 14..10; any
// pattern the table does not list is a Command Error (A34).
struct MethodPattern {
  std::uint16_t bits;
  InterpolationMethod method;
  bool ccw;
};
constexpr MethodPattern kMethodPatterns[] = {
    {cmd_lsw::kLinear, InterpolationMethod::kLinear, false},
    {cmd_lsw::kViaPoint, InterpolationMethod::kViaPoint, false},
    {cmd_lsw::kCwCircular, InterpolationMethod::kCentre, false},
    {cmd_lsw::kCcwCircular, InterpolationMethod::kCentre, true},
    {cmd_lsw::kRadiusMethod | cmd_lsw::kCwCircular, InterpolationMethod::kRadius, false},
    {cmd_lsw::kRadiusMethod | cmd_lsw::kCcwCircular, InterpolationMethod::kRadius, true},
};

// Every coordinate of the block: +-1,073,741,823 (3602 manual Tables 9.23-9.26, the 3602's target
// range).
bool coordinate_in_range(std::int32_t v) noexcept {
  return v >= kRules3602.target_min && v <= kRules3602.target_max;
}

InterpolationFault interpolation_fault(const ImageWords& out, const InterpolatedCommand& c,
                                       std::uint16_t lsw, bool pattern_valid) noexcept {
  if (!pattern_valid || (lsw & ~cmd_lsw::kInterpolatedAllowed) != 0) {
    return InterpolationFault::kPattern;  // 3602-CE-I6, A34
  }
  if (out.w[interp_word::kMsw] != 0) return InterpolationFault::kCommandBits;  // 3602-CE-03
  // 3602-CE-I5 / IP-18: axis 2's command words, and the words the method leaves unused.
  bool reserved_clear = words_zero(out, interp_word::kAxis2Msw, interp_word::kAxis2Lsw);
  if (c.method == InterpolationMethod::kLinear) {
    reserved_clear = reserved_clear && words_zero(out, interp_word::kPointXMsw, 15);
  } else if (c.method == InterpolationMethod::kRadius) {
    reserved_clear = reserved_clear && words_zero(out, interp_word::kPointYMsw, 15);
  }
  if (!reserved_clear) return InterpolationFault::kReserved;
  bool in_range = coordinate_in_range(c.end_x) && coordinate_in_range(c.end_y);
  if (c.method == InterpolationMethod::kViaPoint || c.method == InterpolationMethod::kCentre) {
    in_range = in_range && coordinate_in_range(c.point_x) && coordinate_in_range(c.point_y);
  }
  // A35: the radius word takes any int32 but -2^31 (the geometry then bounds it).
  if (c.method == InterpolationMethod::kRadius) in_range = in_range && c.radius != INT32_MIN;
  return in_range ? InterpolationFault::kNone : InterpolationFault::kRange;
}

}  // namespace

std::optional<InterpolatedCommand> interpolated_from_words(const ImageWords& out) noexcept {
  const auto lsw = static_cast<std::uint16_t>(out.w[interp_word::kLsw]);
  if ((lsw & cmd_lsw::kInterpolation) == 0) return std::nullopt;
  InterpolatedCommand c;
  bool pattern_valid = false;
  for (const MethodPattern& p : kMethodPatterns) {
    if ((lsw & cmd_lsw::kInterpolationMethod) == p.bits) {
      pattern_valid = true;
      c.method = p.method;
      c.ccw = p.ccw;
    }
  }
  c.absolute = (lsw & cmd_lsw::kAbsoluteCoordinates) != 0;
  c.shape = shared::accel_shape(kShapeBits, lsw);  // LSW bits 0/1
  c.speed = split(out, interp_word::kSpeedMsw);
  c.accel = word(out, interp_word::kAccel) * kAccelUnit;
  c.decel = word(out, interp_word::kDecel) * kAccelUnit;
  c.end_x = split(out, interp_word::kEndXMsw);
  c.end_y = split(out, interp_word::kEndYMsw);
  c.point_x = split(out, interp_word::kPointXMsw);
  c.point_y = split(out, interp_word::kPointYMsw);
  c.radius = c.point_x;  // the radius method's words 12 / 13
  c.fault = interpolation_fault(out, c, lsw, pattern_valid);
  return c;
}

namespace {
// Command MSW bits (3602 manual ch. 9 table 9.3). Bits 10 and 14 are reserved, "must be 0": set,
// they are a command the manual does not define (A33) and so a Command Error (3602-CE-10).
constexpr auto kCommandWords =
    shared::command_words_of(kCommandMswBits, cmd_msw::kReserved, kCommandLswBits);
}  // namespace

axis::AxisCommand command_from_words(const ImageWords& out) noexcept {
  axis::AxisCommand c = shared::decode_command_words16(kCommandWords, out, out_word::kMsw);
  const auto lsw = static_cast<std::uint16_t>(out.w[out_word::kLsw]);
  // Words 2-3: target / offset / preset value / registration offset / minimum distance / blend
  // segment length; 4-5 the programmed speed. Binary split: every bit pattern is a number, the
  // axis checks its range (3602-CE-05: +-1,073,741,823).
  c.target = split(out, out_word::kTargetMsw);
  c.speed = split(out, out_word::kSpeedMsw);
  c.accel = word(out, out_word::kAccel) * kAccelUnit;
  c.decel = word(out, out_word::kDecel) * kAccelUnit;
  c.blend_first = blend_first_block(out);
  // 3602-IP-07: an invalid pair is reported through the final-shape slot the shared code already
  // refuses with IP (the block is then an invalid profile block, IP-19).
  if (c.blend_program && has_invalid_pair(out)) c.blend_first.final_shape.reset();
  c.blend_segment = blend_segment_16bit(c, word(out, out_word::kDecel) == 0);
  c.words_invalid = word_rules_broken(out, c, lsw);
  // 3602-CE-03: the broken rule is the interpolation bits with a command bit.
  if (!c.commands.empty() && (lsw & cmd_lsw::kInterpolation))
    c.words_item = &items::kPathWithCommandBit;
  return c;
}

bool gpo_from_words(const ImageWords& out) noexcept {
  return (static_cast<std::uint16_t>(out.w[out_word::kLsw]) & cmd_lsw::kGpo) != 0;
}

std::int32_t wrap_to_int32(std::int64_t v) noexcept {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(static_cast<std::uint64_t>(v)));
}

namespace {
// The status bits that show the shared axis' flags, by their names in the manual.
constexpr auto kMswFlags = shared::status_bits_of<std::uint16_t>(kStatusMswBits);
constexpr auto kLswFlags = shared::status_bits_of<std::uint16_t>(kStatusLswBits);
}  // namespace

void status_to_words(const axis::AxisStatus& s, const StatusExtras& x, ImageWords& in) noexcept {
  std::uint16_t msw = shared::flags_to_word(kMswFlags, s);
  if (x.axis_enabled) msw |= status_msw::kAxisEnabled;

  // Status LSW bits 0..4: capture, external, home, CW input, CCW input (3602 manual Ch.9 "Status
  // Bits LSW"). The axis reports them in InputLine order, where the CW / CCW inputs are the limit
  // lines 4 / 5 and line 3 (a separate E-stop terminal) does not exist on the 3602.
  const auto active = [&s](InputLine l) {
    return (s.inputs_active >> static_cast<unsigned>(l)) & 1u;
  };
  std::uint16_t lsw = shared::flags_to_word(kLswFlags, s);  // blend, registration, proximity
  if (active(InputLine::kCapture)) lsw |= status_lsw::kCaptureActive;
  if (active(InputLine::kExternal)) lsw |= status_lsw::kExternalActive;
  if (active(InputLine::kHome)) lsw |= status_lsw::kHomeActive;
  if (active(InputLine::kCwLimit)) lsw |= status_lsw::kCwActive;
  if (active(InputLine::kCcwLimit)) lsw |= status_lsw::kCcwActive;
  if (x.interpolating) lsw |= status_lsw::kInterpolatedRunning;
  if (x.gpo) lsw |= status_lsw::kGpo;

  in = ImageWords{};
  in.w[in_word::kStatusMsw] = static_cast<std::int16_t>(msw);
  in.w[in_word::kStatusLsw] = static_cast<std::int16_t>(lsw);
  const auto put = [&in](unsigned msw_index, std::int64_t value) {
    const auto pair = words::encode_3602(wrap_to_int32(value));
    in.w[msw_index] = pair.msw;
    in.w[msw_index + 1] = pair.lsw;
  };
  put(in_word::kPositionMsw, s.position);
  put(in_word::kCaptureMsw, s.capture);
}

void configuration_image_to_words(const ImageWords& out, bool configuration_error,
                                  bool axis_enabled, ImageWords& in) noexcept {
  in = ImageWords{};
  // Bits 0..12 echo the configuration MSW; 13..15 are the module's (CfgE, enabled, mode).
  auto w0 = static_cast<std::uint16_t>(static_cast<std::uint16_t>(out.w[out_word::kMsw]) & 0x1FFF);
  if (configuration_error) w0 |= status_msw::kConfigurationError;
  if (axis_enabled) w0 |= status_msw::kAxisEnabled;
  w0 |= status_msw::kConfigMode;
  in.w[in_word::kStatusMsw] = static_cast<std::int16_t>(w0);
  in.w[in_word::kStatusLsw] = static_cast<std::int16_t>(out.w[out_word::kLsw]);
  in.w[in_word::kStartingSpeedMsw] = static_cast<std::int16_t>(out.w[out_word::kStartingSpeedMsw]);
  in.w[in_word::kStartingSpeedLsw] = static_cast<std::int16_t>(out.w[out_word::kStartingSpeedLsw]);
  in.w[in_word::kHomingTimeout] = static_cast<std::int16_t>(out.w[out_word::kHomingTimeout]);
}

}  // namespace stepmod::module::m3602

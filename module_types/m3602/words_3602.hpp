#pragma once
// 3602 backplane words and bits, named as in the 3602 manual (chapters 8 and 9). The only place
// these positions are written down: stepmodctl decodes a 3602's image by these names; the 3602
// dialect (module and PLC side) takes its constants from them (below). Each axis has 8 words at b =
// 8 * axis; indices below are relative to b. 32-bit values are binary splits (3602 manual ch. 9;
// the encoding at the end). Includes nothing but the ground layer.
#include <array>
#include <cstdint>
#include <string_view>

#include "core/bit_table.hpp"
#include "words/word_pair.hpp"

namespace stepmod::words::m3602 {

inline constexpr unsigned kWordsPerAxis = 8;

// Output words per axis, command mode (3602 manual ch. 9 table 9.2); configuration mode
// (table 8.1): 0/1 configuration bits, 2/3 starting speed, 4 homing timeout.
inline constexpr std::array<NamedWord, 8> kOutputWords = {{{0, "Command Bits MSW"},
                                                           {1, "Command Bits LSW"},
                                                           {2, "Target Position MSW"},
                                                           {3, "Target Position LSW"},
                                                           {4, "Programmed Speed MSW"},
                                                           {5, "Programmed Speed LSW"},
                                                           {6, "Acceleration"},
                                                           {7, "Deceleration"}}};

// Input words per axis, command mode (3602 manual ch. 9 table 9.27) and configuration mode
// (table 8.5: echoes).
inline constexpr std::array<NamedWord, 9> kInputWords = {{{0, "Status Bits MSW"},
                                                          {1, "Status Bits LSW"},
                                                          {2, "Position MSW"},
                                                          {3, "Position LSW"},
                                                          {6, "Capture MSW"},
                                                          {7, "Capture LSW"},
                                                          {2, "Starting Speed MSW"},
                                                          {3, "Starting Speed LSW"},
                                                          {4, "Homing Timeout"}}};

// Configuration bits MSW (3602 manual ch. 8 table 8.2, whose bit columns had to be reconstructed).
// CW/CCW input function: 00 not used, 01 overtravel limit, 10 emergency stop, 11 invalid.
inline constexpr std::array<NamedBit, 9> kConfigMswBits = {{
    {0, "Capture Input Enabled"},
    {1, "External Input Enabled"},
    {2, "Home Input Enabled"},
    {3, "CW Input Function (1 = limit, 2 = E-stop)", 2},
    {5, "CCW Input Function (1 = limit, 2 = E-stop)", 2},
    {7, "Backplane Home Proximity"},
    {10, "Step+Direction Output (0 = CW/CCW)"},
    {14, "Disable Axis"},
    {15, "Configuration Mode"},
}};

// Configuration bits LSW: active level per input, 1 = active high (3602 manual ch. 8 table 8.3).
inline constexpr std::array<NamedBit, 5> kConfigLswBits = {{
    {0, "Capture Input Active High"},
    {1, "External Input Active High"},
    {2, "Home Input Active High"},
    {3, "CW Input Active High"},
    {4, "CCW Input Active High"},
}};

// Command bits MSW (3602 manual ch. 9 table 9.3).
inline constexpr std::array<NamedBit, 14> kCommandMswBits = {{
    {0, "Absolute Move"},
    {1, "Relative Move"},
    {2, "Hold Move"},
    {3, "Resume Move"},
    {4, "Immediate Stop"},
    {5, "Find Home CW"},
    {6, "Find Home CCW"},
    {7, "Jog CW (Registration CW)"},
    {8, "Jog CCW (Registration CCW)"},
    {9, "Preset Position"},
    {11, "Reset Errors"},
    {12, "Run Blend Move CW"},
    {13, "Run Blend Move CCW"},
    {15, "Configuration Mode"},
}};

// Command bits LSW (3602 manual ch. 9 table 9.4).
inline constexpr std::array<NamedBit, 13> kCommandLswBits = {{
    {0, "S-Curve Acceleration (0 = constant)"},
    {1, "Trapezoidal S-Curve (0 = triangular)"},
    {2, "Program Minimum Registration Distance"},
    {4, "Program Blend Move"},
    {5, "Blend Move Data Transmit"},
    {6, "Backplane Home Proximity"},
    {7, "General-Purpose Output"},
    {9, "Absolute Interpolated Coordinates"},
    {10, "Linear Interpolated Move"},
    {11, "Via-Point Circular Move"},
    {12, "CW Circular Move"},
    {13, "CCW Circular Move"},
    {14, "Radius Method (with CW / CCW)"},
}};

// Status bits MSW (3602 manual ch. 9).
inline constexpr std::array<NamedBit, 16> kStatusMswBits = {{
    {0, "CW Motion"},
    {1, "CCW Motion"},
    {2, "Hold State"},
    {3, "Axis Stopped"},
    {4, "At Home"},
    {5, "Accelerating"},
    {6, "Decelerating"},
    {7, "Move Complete"},
    {8, "Home Invalid"},
    {9, "Invalid Profile"},
    {10, "Position Invalid"},
    {11, "Input Error"},
    {12, "Command Error"},
    {13, "Configuration Error"},
    {14, "Axis Enabled"},
    {15, "Configuration Mode"},
}};

// Status bits LSW (3602 manual ch. 9).
inline constexpr std::array<NamedBit, 11> kStatusLswBits = {{
    {0, "Capture Input Active"},
    {1, "External Input Active"},
    {2, "Home Input Active"},
    {3, "CW Input Active"},
    {4, "CCW Input Active"},
    {8, "Blend Move Running"},
    {9, "Blend Block Acknowledge"},
    {10, "Min. Registration Distance Set"},
    {11, "Interpolated Move Running"},
    {12, "Backplane Home Proximity Echo"},
    {13, "General-Purpose Output"},
}};

// ---- the constants, looked up in the tables --------------------------------------------------

namespace detail = ::stepmod::bits16;  // field(), unnamed()

// Output words (PLC -> module) of one axis, relative to b = 8 * axis.
namespace out_word {
inline constexpr unsigned kMsw = index_of(kOutputWords, "Command Bits MSW");  // or config MSW
inline constexpr unsigned kLsw = index_of(kOutputWords, "Command Bits LSW");  // or config LSW
inline constexpr unsigned kTargetMsw = index_of(kOutputWords, "Target Position MSW");  // cfg: Vs
inline constexpr unsigned kTargetLsw = index_of(kOutputWords, "Target Position LSW");
inline constexpr unsigned kSpeedMsw = index_of(kOutputWords, "Programmed Speed MSW");  // cfg: 4 =
inline constexpr unsigned kSpeedLsw = index_of(kOutputWords, "Programmed Speed LSW");  // timeout
inline constexpr unsigned kAccel = index_of(kOutputWords, "Acceleration");
inline constexpr unsigned kDecel = index_of(kOutputWords, "Deceleration");
// Configuration mode (3602 manual ch. 8 table 8.1).
inline constexpr unsigned kStartingSpeedMsw = kTargetMsw;
inline constexpr unsigned kStartingSpeedLsw = kTargetLsw;
inline constexpr unsigned kHomingTimeout = kSpeedMsw;
}  // namespace out_word

// Input words (module -> PLC) of one axis.
namespace in_word {
inline constexpr unsigned kStatusMsw = index_of(kInputWords, "Status Bits MSW");
inline constexpr unsigned kStatusLsw = index_of(kInputWords, "Status Bits LSW");
inline constexpr unsigned kPositionMsw = index_of(kInputWords, "Position MSW");
inline constexpr unsigned kCaptureMsw = index_of(kInputWords, "Capture MSW");
inline constexpr unsigned kStartingSpeedMsw = index_of(kInputWords, "Starting Speed MSW");
inline constexpr unsigned kStartingSpeedLsw = index_of(kInputWords, "Starting Speed LSW");
inline constexpr unsigned kHomingTimeout = index_of(kInputWords, "Homing Timeout");
}  // namespace in_word

namespace cfg_msw {
using detail::field;
inline constexpr std::uint16_t kCaptureEnabled = field(kConfigMswBits, "Capture Input Enabled");
inline constexpr std::uint16_t kExternalEnabled = field(kConfigMswBits, "External Input Enabled");
inline constexpr std::uint16_t kHomeEnabled = field(kConfigMswBits, "Home Input Enabled");
inline constexpr std::uint16_t kCwFunction =
    field(kConfigMswBits, "CW Input Function (1 = limit, 2 = E-stop)");
inline constexpr std::uint16_t kCcwFunction =
    field(kConfigMswBits, "CCW Input Function (1 = limit, 2 = E-stop)");
inline constexpr unsigned kCwFunctionShift = 3;
inline constexpr unsigned kCcwFunctionShift = 5;
inline constexpr std::uint16_t kBackplaneProximity =
    field(kConfigMswBits, "Backplane Home Proximity");
inline constexpr std::uint16_t kStepDirOutput =
    field(kConfigMswBits, "Step+Direction Output (0 = CW/CCW)");
inline constexpr std::uint16_t kDisableAxis = field(kConfigMswBits, "Disable Axis");
inline constexpr std::uint16_t kConfigMode = field(kConfigMswBits, "Configuration Mode");
inline constexpr std::uint16_t kReserved = detail::unnamed(kConfigMswBits);  // 8, 9, 11, 12, 13
// Input-function field values (3602 manual ch. 8 table 8.2).
inline constexpr unsigned kFunctionUnused = 0b00;
inline constexpr unsigned kFunctionLimit = 0b01;
inline constexpr unsigned kFunctionEStop = 0b10;
inline constexpr unsigned kFunctionInvalid = 0b11;
}  // namespace cfg_msw

namespace cfg_lsw {
using detail::field;
inline constexpr std::uint16_t kCaptureActiveHigh =
    field(kConfigLswBits, "Capture Input Active High");
inline constexpr std::uint16_t kExternalActiveHigh =
    field(kConfigLswBits, "External Input Active High");
inline constexpr std::uint16_t kHomeActiveHigh = field(kConfigLswBits, "Home Input Active High");
inline constexpr std::uint16_t kCwActiveHigh = field(kConfigLswBits, "CW Input Active High");
inline constexpr std::uint16_t kCcwActiveHigh = field(kConfigLswBits, "CCW Input Active High");
inline constexpr std::uint16_t kReserved = detail::unnamed(kConfigLswBits);  // 5..15
}  // namespace cfg_lsw

namespace cmd_msw {
using detail::field;
inline constexpr std::uint16_t kAbsoluteMove = field(kCommandMswBits, "Absolute Move");
inline constexpr std::uint16_t kRelativeMove = field(kCommandMswBits, "Relative Move");
inline constexpr std::uint16_t kHold = field(kCommandMswBits, "Hold Move");
inline constexpr std::uint16_t kResume = field(kCommandMswBits, "Resume Move");
inline constexpr std::uint16_t kImmediateStop = field(kCommandMswBits, "Immediate Stop");
inline constexpr std::uint16_t kFindHomeCw = field(kCommandMswBits, "Find Home CW");
inline constexpr std::uint16_t kFindHomeCcw = field(kCommandMswBits, "Find Home CCW");
inline constexpr std::uint16_t kJogCw = field(kCommandMswBits, "Jog CW (Registration CW)");
inline constexpr std::uint16_t kJogCcw = field(kCommandMswBits, "Jog CCW (Registration CCW)");
inline constexpr std::uint16_t kPresetPosition = field(kCommandMswBits, "Preset Position");
inline constexpr std::uint16_t kResetErrors = field(kCommandMswBits, "Reset Errors");
inline constexpr std::uint16_t kRunBlendCw = field(kCommandMswBits, "Run Blend Move CW");
inline constexpr std::uint16_t kRunBlendCcw = field(kCommandMswBits, "Run Blend Move CCW");
inline constexpr std::uint16_t kConfigMode = field(kCommandMswBits, "Configuration Mode");
inline constexpr std::uint16_t kReserved = detail::unnamed(kCommandMswBits);  // 10, 14: -> CE
}  // namespace cmd_msw

namespace cmd_lsw {
using detail::field;
inline constexpr std::uint16_t kSCurve =
    field(kCommandLswBits, "S-Curve Acceleration (0 = constant)");
inline constexpr std::uint16_t kTrapezoidalS =
    field(kCommandLswBits, "Trapezoidal S-Curve (0 = triangular)");
inline constexpr std::uint16_t kProgramMinRegistration =
    field(kCommandLswBits, "Program Minimum Registration Distance");
inline constexpr std::uint16_t kProgramBlend = field(kCommandLswBits, "Program Blend Move");
inline constexpr std::uint16_t kBlendTransmit = field(kCommandLswBits, "Blend Move Data Transmit");
inline constexpr std::uint16_t kBackplaneProximity =
    field(kCommandLswBits, "Backplane Home Proximity");
inline constexpr std::uint16_t kGpo = field(kCommandLswBits, "General-Purpose Output");
// Interpolated moves (3602 manual ch. 9 table 9.4): bit 9 selects the coordinate system,
// bits 10..14 the method.
inline constexpr std::uint16_t kAbsoluteCoordinates =
    field(kCommandLswBits, "Absolute Interpolated Coordinates");
inline constexpr std::uint16_t kLinear = field(kCommandLswBits, "Linear Interpolated Move");
inline constexpr std::uint16_t kViaPoint = field(kCommandLswBits, "Via-Point Circular Move");
inline constexpr std::uint16_t kCwCircular = field(kCommandLswBits, "CW Circular Move");
inline constexpr std::uint16_t kCcwCircular = field(kCommandLswBits, "CCW Circular Move");
inline constexpr std::uint16_t kRadiusMethod =
    field(kCommandLswBits, "Radius Method (with CW / CCW)");
inline constexpr std::uint16_t kInterpolationMethod =
    kLinear | kViaPoint | kCwCircular | kCcwCircular | kRadiusMethod;
// Bits 9..14: any of them set makes the LSW an interpolated command (3602-CE-03 with an MSW bit).
inline constexpr std::uint16_t kInterpolation = kAbsoluteCoordinates | kInterpolationMethod;
static_assert(kInterpolation == 0x7E00);
// What else an interpolated command's LSW may hold: the acceleration type and the GPO level.
inline constexpr std::uint16_t kInterpolatedAllowed =
    kInterpolation | kSCurve | kTrapezoidalS | kGpo;
}  // namespace cmd_lsw

// The interpolated move block (3602 manual ch. 9 tables 9.23-9.26): all sixteen output words of the
// module, indices from word 0 of axis 1. Axis 2's command words 8 / 9 must be 0.
namespace interp_word {
inline constexpr unsigned kMsw = out_word::kMsw;  // 16#0000
inline constexpr unsigned kLsw = out_word::kLsw;  // bits 9..14, accel type, GPO
inline constexpr unsigned kSpeedMsw = 2;          // vector speed, 2 / 3
inline constexpr unsigned kAccel = 4;             // vector accel, steps/ms/s
inline constexpr unsigned kDecel = 5;             // vector decel
inline constexpr unsigned kEndXMsw = 6;           // end point X, 6 / 7
inline constexpr unsigned kAxis2Msw = kWordsPerAxis + out_word::kMsw;  // 8: reserved, 0
inline constexpr unsigned kAxis2Lsw = kWordsPerAxis + out_word::kLsw;  // 9: reserved, 0
inline constexpr unsigned kEndYMsw = 10;                               // end point Y, 10 / 11
inline constexpr unsigned kPointXMsw = 12;  // via X / centre X / signed radius, 12 / 13
inline constexpr unsigned kPointYMsw = 14;  // via Y / centre Y, 14 / 15 (radius: reserved, 0)
}  // namespace interp_word

namespace status_msw {
using detail::field;
inline constexpr std::uint16_t kMovingCw = field(kStatusMswBits, "CW Motion");
inline constexpr std::uint16_t kMovingCcw = field(kStatusMswBits, "CCW Motion");
inline constexpr std::uint16_t kHoldState = field(kStatusMswBits, "Hold State");
inline constexpr std::uint16_t kStopped = field(kStatusMswBits, "Axis Stopped");
inline constexpr std::uint16_t kAtHome = field(kStatusMswBits, "At Home");
inline constexpr std::uint16_t kAccelerating = field(kStatusMswBits, "Accelerating");
inline constexpr std::uint16_t kDecelerating = field(kStatusMswBits, "Decelerating");
inline constexpr std::uint16_t kMoveComplete = field(kStatusMswBits, "Move Complete");
inline constexpr std::uint16_t kHomeInvalid = field(kStatusMswBits, "Home Invalid");
inline constexpr std::uint16_t kInvalidProfile = field(kStatusMswBits, "Invalid Profile");
inline constexpr std::uint16_t kPositionInvalid = field(kStatusMswBits, "Position Invalid");
inline constexpr std::uint16_t kInputError = field(kStatusMswBits, "Input Error");
inline constexpr std::uint16_t kCommandError = field(kStatusMswBits, "Command Error");
inline constexpr std::uint16_t kConfigurationError = field(kStatusMswBits, "Configuration Error");
inline constexpr std::uint16_t kAxisEnabled = field(kStatusMswBits, "Axis Enabled");
inline constexpr std::uint16_t kConfigMode = field(kStatusMswBits, "Configuration Mode");
}  // namespace status_msw

namespace status_lsw {
using detail::field;
inline constexpr std::uint16_t kCaptureActive = field(kStatusLswBits, "Capture Input Active");
inline constexpr std::uint16_t kExternalActive = field(kStatusLswBits, "External Input Active");
inline constexpr std::uint16_t kHomeActive = field(kStatusLswBits, "Home Input Active");
inline constexpr std::uint16_t kCwActive = field(kStatusLswBits, "CW Input Active");
inline constexpr std::uint16_t kCcwActive = field(kStatusLswBits, "CCW Input Active");
inline constexpr std::uint16_t kBlendRunning = field(kStatusLswBits, "Blend Move Running");
inline constexpr std::uint16_t kBlendAcknowledge = field(kStatusLswBits, "Blend Block Acknowledge");
inline constexpr std::uint16_t kMinRegistrationSet =
    field(kStatusLswBits, "Min. Registration Distance Set");
inline constexpr std::uint16_t kInterpolatedRunning =
    field(kStatusLswBits, "Interpolated Move Running");
inline constexpr std::uint16_t kProximityEcho =
    field(kStatusLswBits, "Backplane Home Proximity Echo");
inline constexpr std::uint16_t kGpo = field(kStatusLswBits, "General-Purpose Output");
}  // namespace status_lsw

}  // namespace stepmod::words::m3602

// ---- the number encoding: binary split, 3602 manual ch. 9 ---------------------------------------
namespace stepmod::words {

// value = MSW << 16 | LSW (two's complement over both words); only the low 16 bits of each count.
std::int32_t decode_3602(std::int32_t msw, std::int32_t lsw) noexcept;
WordPair encode_3602(std::int32_t value) noexcept;

}  // namespace stepmod::words

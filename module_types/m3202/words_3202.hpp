#pragma once
// 3202 backplane words and bits, named as in the 3202 manual
// (3202 manual). The only place these positions are written down: each DINT's bits
// are a constexpr table (bit, name), the constants below are looked up in the tables by name (as
// in words_3601.hpp), and stepmodctl shows the same names. Each channel has 8 DINTs at b = 8 *
// channel; indices below are relative to b. Values are native 32-bit integers (3202 manual ch. 5).
// Includes nothing but the ground layer.
#include <array>
#include <cstdint>

#include "core/bit_table.hpp"
#include "words/shared_config_bits.hpp"

namespace stepmod::words::m3202 {

inline constexpr unsigned kWordsPerChannel = 8;

// Output DINTs per channel, command mode (3202 manual ch. 5); configuration mode (ch. 3): 0
// configuration bits, 1 starting speed.
inline constexpr std::array<NamedWord, 5> kOutputWords = {{{0, "Command Word"},
                                                           {1, "Target Position"},
                                                           {2, "Programmed Speed"},
                                                           {3, "Acceleration"},
                                                           {4, "Deceleration"}}};

// Input DINTs per channel, command mode (3202 manual ch. 6) and configuration mode (ch. 3).
inline constexpr std::array<NamedWord, 6> kInputWords = {{{0, "Status Word"},
                                                          {1, "Position"},
                                                          {2, "Encoder"},
                                                          {3, "Capture"},
                                                          {1, "Starting Speed"},
                                                          {3, "Firmware Revision"}}};

// Configuration bits (3202 manual ch. 3).
inline constexpr std::array<NamedBit, 19> kConfigBits = {{
    {0, "Capture Input Used"},
    {1, "External Input Used"},
    {2, "Home Input Used"},
    {3, "E-Stop Input Used"},
    {4, "CW Limit Used"},
    {5, "CCW Limit Used"},
    {6, "Backplane Home Proximity"},
    {8, "Quadrature Encoder"},
    {9, "Diagnostic Feedback"},
    {10, "Step+Direction Output (0 = CW/CCW)"},
    {12, "Marker Homing (0 = home switch)"},
    {16, "Capture Input Active High"},
    {17, "External Input Active High"},
    {18, "Home Input Active High"},
    {19, "E-Stop Input Active High"},
    {20, "CW Limit Active High"},
    {21, "CCW Limit Active High"},
    {28, "Disable Channel"},
    {31, "Configuration Mode"},
}};

// Configuration-mode echo (3202 manual ch. 3): the configuration bits except these.
inline constexpr std::array<NamedBit, 4> kConfigEchoBits = {{
    {13, "Configuration Error"},
    {28, "Channel Disabled"},
    {30, "Module OK"},
    {31, "Configuration Mode"},
}};

// Command word (3202 manual ch. 5).
inline constexpr std::array<NamedBit, 19> kCommandBits = {{
    {0, "Absolute Move"},
    {1, "Relative Move"},
    {2, "Hold Move"},
    {3, "Resume Move"},
    {4, "Immediate Stop"},
    {5, "Find Home CW"},
    {6, "Find Home CCW"},
    {7, "Manual Move CW"},
    {8, "Manual Move CCW"},
    {9, "Preset Position"},
    {10, "Preset Encoder"},
    {11, "Reset Errors"},
    {12, "Run Blend Move CW"},
    {13, "Run Blend Move CCW"},
    {16, "S-Curve Acceleration (0 = constant)"},
    {17, "Trapezoidal S-Curve (0 = triangular)"},
    {18, "Encoder Move"},
    {29, "Backplane Home Proximity"},
    {31, "Configuration Mode"},
}};

// Status word (3202 manual ch. 6). Note Home Invalid and Invalid Profile sit at bits 14/15 here,
// not at 8/9 as on the 3601/3602.
inline constexpr std::array<NamedBit, 25> kStatusBits = {{
    {0, "Moving CW"},
    {1, "Moving CCW"},
    {2, "Hold State"},
    {3, "Stopped"},
    {4, "At Home"},
    {5, "Accelerating"},
    {6, "Decelerating"},
    {7, "Move Complete"},
    {8, "Blend Move Running"},
    {10, "Position Invalid"},
    {11, "Input Error"},
    {12, "Command Error"},
    {13, "Configuration Error"},
    {14, "Home Invalid"},
    {15, "Invalid Profile"},
    {16, "Capture Input Active"},
    {17, "External Input Active"},
    {18, "Home Input Active"},
    {19, "E-Stop Input Active"},
    {20, "CW Limit Active"},
    {21, "CCW Limit Active"},
    {28, "Channel Disabled"},
    {29, "Backplane Home Proximity Echo"},
    {30, "Module OK"},
    {31, "Configuration Mode"},
}};

// ---- the constants, looked up in the tables --------------------------------------------------

namespace detail = ::stepmod::bits32;  // field(), unnamed()

namespace cfg_bit {
using detail::field;
inline constexpr std::uint32_t kCaptureUsed = field(kConfigBits, "Capture Input Used");
inline constexpr std::uint32_t kExternalUsed = field(kConfigBits, "External Input Used");
inline constexpr std::uint32_t kHomeUsed = field(kConfigBits, "Home Input Used");
inline constexpr std::uint32_t kEStopUsed = field(kConfigBits, "E-Stop Input Used");
inline constexpr std::uint32_t kCwLimitUsed = field(kConfigBits, "CW Limit Used");
inline constexpr std::uint32_t kCcwLimitUsed = field(kConfigBits, "CCW Limit Used");
inline constexpr std::uint32_t kBackplaneProximity = field(kConfigBits, "Backplane Home Proximity");
inline constexpr std::uint32_t kQuadratureEncoder = field(kConfigBits, "Quadrature Encoder");
inline constexpr std::uint32_t kDiagnosticFeedback = field(kConfigBits, "Diagnostic Feedback");
inline constexpr std::uint32_t kStepDirOutput =  // 0 = CW/CCW pulse outputs
    field(kConfigBits, "Step+Direction Output (0 = CW/CCW)");
inline constexpr std::uint32_t kMarkerHoming =  // 0 = home-switch homing
    field(kConfigBits, "Marker Homing (0 = home switch)");
// Bits 16..21: active levels, in InputLine order (the order of the "used" bits 0..5).
inline constexpr unsigned kActiveLevelShift = bit_of(kConfigBits, "Capture Input Active High");
inline constexpr std::uint32_t kInputsUsed =
    kCaptureUsed | kExternalUsed | kHomeUsed | kEStopUsed | kCwLimitUsed | kCcwLimitUsed;
inline constexpr std::uint32_t kActiveLevels =
    field(kConfigBits, "Capture Input Active High") |
    field(kConfigBits, "External Input Active High") |
    field(kConfigBits, "Home Input Active High") | field(kConfigBits, "E-Stop Input Active High") |
    field(kConfigBits, "CW Limit Active High") | field(kConfigBits, "CCW Limit Active High");
inline constexpr std::uint32_t kDisable = field(kConfigBits, "Disable Channel");
inline constexpr std::uint32_t kConfigMode = field(kConfigBits, "Configuration Mode");
// 3202-CFG-09: reserved bits 7, 11, 13-15, 22-27, 29, 30 (the bits the table does not name).
inline constexpr std::uint32_t kReserved = detail::unnamed(kConfigBits);
// The bits the 3601 names alike, where the DINT keeps them (words/shared_config_bits.hpp).
inline constexpr SharedConfigMasks kShared = shared_config_masks(kConfigBits);
}  // namespace cfg_bit

namespace cmd_bit {
using detail::field;
inline constexpr std::uint32_t kAbsoluteMove = field(kCommandBits, "Absolute Move");
inline constexpr std::uint32_t kRelativeMove = field(kCommandBits, "Relative Move");
inline constexpr std::uint32_t kHold = field(kCommandBits, "Hold Move");
inline constexpr std::uint32_t kResume = field(kCommandBits, "Resume Move");
inline constexpr std::uint32_t kImmediateStop = field(kCommandBits, "Immediate Stop");
inline constexpr std::uint32_t kFindHomeCw = field(kCommandBits, "Find Home CW");
inline constexpr std::uint32_t kFindHomeCcw = field(kCommandBits, "Find Home CCW");
inline constexpr std::uint32_t kManualCw = field(kCommandBits, "Manual Move CW");
inline constexpr std::uint32_t kManualCcw = field(kCommandBits, "Manual Move CCW");
inline constexpr std::uint32_t kPresetPosition = field(kCommandBits, "Preset Position");
inline constexpr std::uint32_t kPresetEncoder = field(kCommandBits, "Preset Encoder");
inline constexpr std::uint32_t kResetErrors = field(kCommandBits, "Reset Errors");
inline constexpr std::uint32_t kRunBlendCw = field(kCommandBits, "Run Blend Move CW");
inline constexpr std::uint32_t kRunBlendCcw = field(kCommandBits, "Run Blend Move CCW");
inline constexpr std::uint32_t kSCurve = field(kCommandBits, "S-Curve Acceleration (0 = constant)");
inline constexpr std::uint32_t kTrapezoidalS =
    field(kCommandBits, "Trapezoidal S-Curve (0 = triangular)");
inline constexpr std::uint32_t kEncoderMove = field(kCommandBits, "Encoder Move");
inline constexpr std::uint32_t kBackplaneProximity =
    field(kCommandBits, "Backplane Home Proximity");
inline constexpr std::uint32_t kConfigMode = field(kCommandBits, "Configuration Mode");
// 3202-CE-24, A33: reserved bits 14, 15, 19-28, 30 (unnamed) count as an extra (undefined) command.
inline constexpr std::uint32_t kReserved = detail::unnamed(kCommandBits);
}  // namespace cmd_bit

namespace status_bit {
using detail::field;
inline constexpr std::uint32_t kMovingCw = field(kStatusBits, "Moving CW");
inline constexpr std::uint32_t kMovingCcw = field(kStatusBits, "Moving CCW");
inline constexpr std::uint32_t kHoldState = field(kStatusBits, "Hold State");
inline constexpr std::uint32_t kStopped = field(kStatusBits, "Stopped");
inline constexpr std::uint32_t kAtHome = field(kStatusBits, "At Home");
inline constexpr std::uint32_t kAccelerating = field(kStatusBits, "Accelerating");
inline constexpr std::uint32_t kDecelerating = field(kStatusBits, "Decelerating");
inline constexpr std::uint32_t kMoveComplete = field(kStatusBits, "Move Complete");
inline constexpr std::uint32_t kBlendRunning = field(kStatusBits, "Blend Move Running");
inline constexpr std::uint32_t kPositionInvalid = field(kStatusBits, "Position Invalid");
inline constexpr std::uint32_t kInputError = field(kStatusBits, "Input Error");
inline constexpr std::uint32_t kCommandError = field(kStatusBits, "Command Error");
inline constexpr std::uint32_t kConfigurationError = field(kStatusBits, "Configuration Error");
inline constexpr std::uint32_t kHomeInvalid = field(kStatusBits, "Home Invalid");
inline constexpr std::uint32_t kInvalidProfile = field(kStatusBits, "Invalid Profile");
// Bits 16..21: inputs active, in InputLine order.
inline constexpr unsigned kInputShift = bit_of(kStatusBits, "Capture Input Active");
inline constexpr std::uint32_t kChannelDisabled = field(kStatusBits, "Channel Disabled");
inline constexpr std::uint32_t kProximityEcho = field(kStatusBits, "Backplane Home Proximity Echo");
inline constexpr std::uint32_t kModuleOk = field(kStatusBits, "Module OK");
inline constexpr std::uint32_t kConfigMode = field(kStatusBits, "Configuration Mode");
}  // namespace status_bit

// Word indices relative to the channel's base (3202 manual ch. 3, 5, 6).
namespace out_word {
inline constexpr unsigned kCommand = 0;  // configuration mode: configuration bits
inline constexpr unsigned kTarget = 1;   // configuration mode: starting speed
inline constexpr unsigned kSpeed = 2;
inline constexpr unsigned kAccel = 3;
inline constexpr unsigned kDecel = 4;
inline constexpr unsigned kFirstReserved = 5;  // 5..7 must be 0 (3202-CE-05)
}  // namespace out_word
namespace in_word {
inline constexpr unsigned kStatus = 0;
inline constexpr unsigned kPosition = 1;  // configuration mode: starting speed mirror
inline constexpr unsigned kEncoder = 2;
inline constexpr unsigned kCapture = 3;  // configuration mode: firmware revision
}  // namespace in_word

// The firmware revision reported in configuration mode (major in bits 31-16, minor in 15-0).
// 3.1: capture without encoder is valid (3202-CFG-08 applies to <= 2.2 only).
inline constexpr std::uint32_t kFirmwareMajor = 3;
inline constexpr std::uint32_t kFirmwareMinor = 1;

// DINT indices of the message (3202 manual ch. 5).
namespace msg_dint {
inline constexpr unsigned kChannel = 0;       // 1 or 2
inline constexpr unsigned kSegments = 1;      // 2 ... 16
inline constexpr unsigned kTypePairs = 2;     // segment n: bits 2n-1 : 2n-2
inline constexpr unsigned kFinalDecel = 3;    // type in bits 31-30, value in 29-0
inline constexpr unsigned kFirstSegment = 4;  // length, speed, rate per segment
inline constexpr unsigned kPerSegment = 3;
inline constexpr unsigned kCount = 52;
}  // namespace msg_dint

// The message result written to the mailbox (the image's message mailbox: 0 accepted, otherwise the
// error is reported in the status bits as the manual says).
inline constexpr std::int32_t kMessageAccepted = 0;
inline constexpr std::int32_t kMessageRefused = 1;

constexpr unsigned channel_base(unsigned channel) noexcept {
  return channel * kWordsPerChannel;
}

}  // namespace stepmod::words::m3202

// ---- the number encoding: native DINT, 3202 manual ch. 5 ----------------------------------------
namespace stepmod::words {

constexpr std::int32_t decode_3202(std::int32_t w) noexcept {
  return w;
}
constexpr std::int32_t encode_3202(std::int32_t v) noexcept {
  return v;
}

}  // namespace stepmod::words

#pragma once
// 3202 backplane words and bits, named as in the 3202 manual
// (shared/spec/manuals/002_f6a32b63084cb2fa.txt; digest MODULES.md section 5). Tables only for now:
// stepmodctl decodes a 3202's image by these names; the 3202 dialect (module and PLC side) will
// take its constants from them the way words_3601.hpp does. Each channel has 8 DINTs at b = 8 *
// channel; indices below are relative to b. Values are native 32-bit integers (digest 2.3).
// Header-only, ground layer only.
#include <array>
#include <cstdint>

#include "core/bit_table.hpp"

namespace stepmod::module::m3202 {

inline constexpr unsigned kWordsPerChannel = 8;

// Output DINTs per channel, command mode (digest 5.4); configuration mode (5.1): 0 configuration
// bits, 1 starting speed.
inline constexpr std::array<NamedWord, 5> kOutputWords = {{{0, "Command Word"},
                                                           {1, "Target Position"},
                                                           {2, "Programmed Speed"},
                                                           {3, "Acceleration"},
                                                           {4, "Deceleration"}}};

// Input DINTs per channel, command mode (digest 5.6) and configuration mode (5.3).
inline constexpr std::array<NamedWord, 6> kInputWords = {{{0, "Status Word"},
                                                          {1, "Position"},
                                                          {2, "Encoder"},
                                                          {3, "Capture"},
                                                          {1, "Starting Speed"},
                                                          {3, "Firmware Revision"}}};

// Configuration bits (digest 5.2).
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

// Configuration-mode echo (digest 5.3): the configuration bits except these.
inline constexpr std::array<NamedBit, 4> kConfigEchoBits = {{
    {13, "Configuration Error"},
    {28, "Channel Disabled"},
    {30, "Module OK"},
    {31, "Configuration Mode"},
}};

// Command word (digest 5.5).
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

// Status word (digest 5.7). Note Home Invalid and Invalid Profile sit at bits 14/15 here, not
// at 8/9 as on the 3601/3602.
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

// Bit masks by name, for the dialect (module side and PLC side). Values from the tables above.
namespace cfg_bit {
inline constexpr std::uint32_t kCaptureUsed = 1u << 0;
inline constexpr std::uint32_t kExternalUsed = 1u << 1;
inline constexpr std::uint32_t kHomeUsed = 1u << 2;
inline constexpr std::uint32_t kEStopUsed = 1u << 3;
inline constexpr std::uint32_t kCwLimitUsed = 1u << 4;
inline constexpr std::uint32_t kCcwLimitUsed = 1u << 5;
inline constexpr std::uint32_t kBackplaneProximity = 1u << 6;
inline constexpr std::uint32_t kQuadratureEncoder = 1u << 8;
inline constexpr std::uint32_t kDiagnosticFeedback = 1u << 9;
inline constexpr std::uint32_t kStepDirOutput = 1u << 10;
inline constexpr std::uint32_t kMarkerHoming = 1u << 12;
inline constexpr unsigned kActiveLevelShift = 16;  // bits 16..21: active levels, InputLine order
inline constexpr std::uint32_t kInputsUsed = 0x3Fu;
inline constexpr std::uint32_t kActiveLevels = 0x3Fu << kActiveLevelShift;
inline constexpr std::uint32_t kDisable = 1u << 28;
inline constexpr std::uint32_t kConfigMode = 1u << 31;
// 3202-CFG-09: reserved bits 7, 11, 13-15, 22-27, 29, 30.
inline constexpr std::uint32_t kReserved =
    (1u << 7) | (1u << 11) | (0x7u << 13) | (0x3Fu << 22) | (1u << 29) | (1u << 30);
}  // namespace cfg_bit

namespace cmd_bit {
inline constexpr std::uint32_t kAbsoluteMove = 1u << 0;
inline constexpr std::uint32_t kRelativeMove = 1u << 1;
inline constexpr std::uint32_t kHold = 1u << 2;
inline constexpr std::uint32_t kResume = 1u << 3;
inline constexpr std::uint32_t kImmediateStop = 1u << 4;
inline constexpr std::uint32_t kFindHomeCw = 1u << 5;
inline constexpr std::uint32_t kFindHomeCcw = 1u << 6;
inline constexpr std::uint32_t kManualCw = 1u << 7;
inline constexpr std::uint32_t kManualCcw = 1u << 8;
inline constexpr std::uint32_t kPresetPosition = 1u << 9;
inline constexpr std::uint32_t kPresetEncoder = 1u << 10;
inline constexpr std::uint32_t kResetErrors = 1u << 11;
inline constexpr std::uint32_t kRunBlendCw = 1u << 12;
inline constexpr std::uint32_t kRunBlendCcw = 1u << 13;
inline constexpr std::uint32_t kSCurve = 1u << 16;
inline constexpr std::uint32_t kTrapezoidalS = 1u << 17;
inline constexpr std::uint32_t kEncoderMove = 1u << 18;
inline constexpr std::uint32_t kBackplaneProximity = 1u << 29;
inline constexpr std::uint32_t kConfigMode = 1u << 31;
// 3202-CE-24, A33: reserved bits 14, 15, 19-28, 30 count as an extra (undefined) command.
inline constexpr std::uint32_t kReserved = (1u << 14) | (1u << 15) | (0x3FFu << 19) | (1u << 30);
}  // namespace cmd_bit

namespace status_bit {
inline constexpr std::uint32_t kMovingCw = 1u << 0;
inline constexpr std::uint32_t kMovingCcw = 1u << 1;
inline constexpr std::uint32_t kHoldState = 1u << 2;
inline constexpr std::uint32_t kStopped = 1u << 3;
inline constexpr std::uint32_t kAtHome = 1u << 4;
inline constexpr std::uint32_t kAccelerating = 1u << 5;
inline constexpr std::uint32_t kDecelerating = 1u << 6;
inline constexpr std::uint32_t kMoveComplete = 1u << 7;
inline constexpr std::uint32_t kBlendRunning = 1u << 8;
inline constexpr std::uint32_t kPositionInvalid = 1u << 10;
inline constexpr std::uint32_t kInputError = 1u << 11;
inline constexpr std::uint32_t kCommandError = 1u << 12;
inline constexpr std::uint32_t kConfigurationError = 1u << 13;
inline constexpr std::uint32_t kHomeInvalid = 1u << 14;
inline constexpr std::uint32_t kInvalidProfile = 1u << 15;
inline constexpr unsigned kInputShift = 16;  // bits 16..21: inputs active, InputLine order
inline constexpr std::uint32_t kChannelDisabled = 1u << 28;
inline constexpr std::uint32_t kProximityEcho = 1u << 29;
inline constexpr std::uint32_t kModuleOk = 1u << 30;
inline constexpr std::uint32_t kConfigMode = 1u << 31;
}  // namespace status_bit

// Word indices relative to the channel's base (digest 5.1, 5.3, 5.4, 5.6).
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

constexpr unsigned channel_base(unsigned channel) noexcept {
  return channel * kWordsPerChannel;
}

}  // namespace stepmod::module::m3202

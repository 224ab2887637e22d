#pragma once
// 3601 backplane words and bits, named as in the 3601 manual (chapters 3, 5 and 6). The only place
// these positions are written down: each word's bits are a constexpr table (bit, name), the
// constants below are looked up in the tables by name, and stepmodctl shows the same names; the
// decimal split at the end. Includes nothing but the ground layer: the emulator (module/), the PLC
// side (plc/) and stepmodctl include it.
#include <array>
#include <cstdint>

#include <optional>

#include "core/bit_table.hpp"
#include "words/shared_config_bits.hpp"
#include "words/word_pair.hpp"

namespace stepmod::words::m3601 {

inline constexpr unsigned kWords = 8;
inline constexpr std::uint16_t bit(unsigned n) {
  return static_cast<std::uint16_t>(1u << n);
}

// ---- the tables (3601 manual ch. 3, 5, 6) -------------------------------------------------------

// Output words (PLC -> module), command mode (3601 manual ch. 5); configuration mode uses words
// 0..3 for the configuration bits and the starting speed (3601 manual ch. 3).
inline constexpr std::array<NamedWord, 8> kOutputWords = {{{0, "Command Word MSW"},
                                                           {1, "Command Word LSW"},
                                                           {2, "Target Position MSW"},
                                                           {3, "Target Position LSW"},
                                                           {4, "Programmed Speed MSW"},
                                                           {5, "Programmed Speed LSW"},
                                                           {6, "Acceleration"},
                                                           {7, "Deceleration"}}};

// Input words (module -> PLC), command mode (3601 manual ch. 6) and configuration mode (3601 manual
// ch. 3: words 0..3 mirror the accepted configuration, 6..7 the firmware revision).
inline constexpr std::array<NamedWord, 12> kInputWords = {{{0, "Status Word MSW"},
                                                           {1, "Status Word LSW"},
                                                           {2, "Position MSW"},
                                                           {3, "Position LSW"},
                                                           {4, "Encoder MSW"},
                                                           {5, "Encoder LSW"},
                                                           {6, "Capture MSW"},
                                                           {7, "Capture LSW"},
                                                           {2, "Starting Speed MSW"},
                                                           {3, "Starting Speed LSW"},
                                                           {6, "Firmware Major Revision"},
                                                           {7, "Firmware Minor Revision"}}};

// Configuration bits MSW (output word 0 in configuration mode, 3601 manual ch. 3). Bits 7, 11, 13
// and 14 are reserved.
inline constexpr std::array<NamedBit, 12> kConfigMswBits = {{
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
    {15, "Configuration Mode"},
}};

// Configuration bits LSW: active level per input, 1 = active high (3601 manual ch. 3). Bit n
// belongs to the input whose "used" bit is bit n of the MSW. Bits 6..15 are reserved.
inline constexpr std::array<NamedBit, 6> kConfigLswBits = {{
    {0, "Capture Input Active High"},
    {1, "External Input Active High"},
    {2, "Home Input Active High"},
    {3, "E-Stop Input Active High"},
    {4, "CW Limit Active High"},
    {5, "CCW Limit Active High"},
}};

// Command word MSW (output word 0 in command mode, 3601 manual ch. 5). Bits 0..13 are commands; at
// most one may be set. Bit 14 is reserved.
inline constexpr std::array<NamedBit, 15> kCommandMswBits = {{
    {0, "Absolute Move"},
    {1, "Relative Move"},
    {2, "Hold Move"},
    {3, "Resume Move"},
    {4, "Immediate Stop"},
    {5, "Find Home CW"},
    {6, "Find Home CCW"},
    {7, "Manual Move CW"},   // level; also follower "same sense"
    {8, "Manual Move CCW"},  // level; also follower "reverse"
    {9, "Preset Position"},
    {10, "Preset Encoder"},
    {11, "Reset Errors"},
    {12, "Run Blend Move CW"},
    {13, "Run Blend Move CCW"},
    {15, "Configuration Mode"},
}};

// Command word LSW (output word 1 in command mode, 3601 manual ch. 5).
inline constexpr std::array<NamedBit, 8> kCommandLswBits = {{
    {0, "S-Curve Acceleration (0 = constant)"},
    {1, "Trapezoidal S-Curve (0 = triangular)"},
    {2, "Encoder Move"},
    {7, "Encoder Follower"},
    {8, "Program Blend Move"},
    {9, "Blend Move Data Transmit"},
    {10, "Store Minimum Registration Distance"},
    {12, "Backplane Home Proximity"},
}};

// Status word MSW (input word 0, 3601 manual ch. 6).
inline constexpr std::array<NamedBit, 16> kStatusMswBits = {{
    {0, "Moving CW"},
    {1, "Moving CCW"},
    {2, "Hold State"},
    {3, "Stopped"},
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
    {14, "Module OK"},
    {15, "Configuration Mode"},
}};

// Status word LSW (input word 1, 3601 manual ch. 6). Bits 0..5: logical input states, in the order
// of the configuration bits (capture, external, home, E-stop, CW limit, CCW limit).
inline constexpr std::array<NamedBit, 11> kStatusLswBits = {{
    {0, "Capture Input Active"},
    {1, "External Input Active"},
    {2, "Home Input Active"},
    {3, "E-Stop Input Active"},
    {4, "CW Limit Active"},
    {5, "CCW Limit Active"},
    {7, "Encoder Follower Mode"},
    {8, "Blend Move Running"},
    {9, "Blend Block Acknowledge"},
    {10, "Min. Registration Distance Set"},
    {12, "Backplane Home Proximity Echo"},
}};

// ---- the constants, looked up in the tables --------------------------------------------------

namespace detail = ::stepmod::bits16;  // field(), unnamed()

// Output words (PLC -> module), both modes.
namespace out_word {
inline constexpr unsigned kMsw = index_of(kOutputWords, "Command Word MSW");  // or config MSW
inline constexpr unsigned kLsw = index_of(kOutputWords, "Command Word LSW");  // or config LSW
inline constexpr unsigned kTargetMsw = index_of(kOutputWords, "Target Position MSW");  // config: Vs
inline constexpr unsigned kTargetLsw = index_of(kOutputWords, "Target Position LSW");
inline constexpr unsigned kSpeedMsw = index_of(kOutputWords, "Programmed Speed MSW");
inline constexpr unsigned kSpeedLsw = index_of(kOutputWords, "Programmed Speed LSW");
inline constexpr unsigned kAccel = index_of(kOutputWords, "Acceleration");
inline constexpr unsigned kDecel = index_of(kOutputWords, "Deceleration");
}  // namespace out_word

// Input words (module -> PLC).
namespace in_word {
inline constexpr unsigned kStatusMsw = index_of(kInputWords, "Status Word MSW");
inline constexpr unsigned kStatusLsw = index_of(kInputWords, "Status Word LSW");
inline constexpr unsigned kPositionMsw = index_of(kInputWords, "Position MSW");
inline constexpr unsigned kPositionLsw = index_of(kInputWords, "Position LSW");
inline constexpr unsigned kEncoderMsw = index_of(kInputWords, "Encoder MSW");
inline constexpr unsigned kEncoderLsw = index_of(kInputWords, "Encoder LSW");
inline constexpr unsigned kCaptureMsw = index_of(kInputWords, "Capture MSW");
inline constexpr unsigned kCaptureLsw = index_of(kInputWords, "Capture LSW");
// Configuration mode.
inline constexpr unsigned kStartingSpeedMsw = index_of(kInputWords, "Starting Speed MSW");
inline constexpr unsigned kStartingSpeedLsw = index_of(kInputWords, "Starting Speed LSW");
inline constexpr unsigned kFirmwareMajor = index_of(kInputWords, "Firmware Major Revision");
inline constexpr unsigned kFirmwareMinor = index_of(kInputWords, "Firmware Minor Revision");
}  // namespace in_word

namespace cfg_msw {
using detail::field;
inline constexpr std::uint16_t kCaptureUsed = field(kConfigMswBits, "Capture Input Used");
inline constexpr std::uint16_t kExternalUsed = field(kConfigMswBits, "External Input Used");
inline constexpr std::uint16_t kHomeUsed = field(kConfigMswBits, "Home Input Used");
inline constexpr std::uint16_t kEStopUsed = field(kConfigMswBits, "E-Stop Input Used");
inline constexpr std::uint16_t kCwLimitUsed = field(kConfigMswBits, "CW Limit Used");
inline constexpr std::uint16_t kCcwLimitUsed = field(kConfigMswBits, "CCW Limit Used");
inline constexpr std::uint16_t kBackplaneProximity =
    field(kConfigMswBits, "Backplane Home Proximity");
inline constexpr std::uint16_t kQuadratureEncoder = field(kConfigMswBits, "Quadrature Encoder");
inline constexpr std::uint16_t kDiagnosticFeedback = field(kConfigMswBits, "Diagnostic Feedback");
inline constexpr std::uint16_t kStepDirOutput =  // 0 = CW/CCW pulse outputs
    field(kConfigMswBits, "Step+Direction Output (0 = CW/CCW)");
inline constexpr std::uint16_t kMarkerHoming =  // 0 = home-switch homing
    field(kConfigMswBits, "Marker Homing (0 = home switch)");
inline constexpr std::uint16_t kConfigMode = field(kConfigMswBits, "Configuration Mode");
inline constexpr std::uint16_t kReserved = detail::unnamed(kConfigMswBits);
// The bits the 3202 names alike, where the MSW keeps them (words/shared_config_bits.hpp).
inline constexpr SharedConfigMasks kShared = shared_config_masks(kConfigMswBits);
}  // namespace cfg_msw

namespace cfg_lsw {
inline constexpr std::uint16_t kReserved = detail::unnamed(kConfigLswBits);
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
inline constexpr std::uint16_t kManualCw = field(kCommandMswBits, "Manual Move CW");
inline constexpr std::uint16_t kManualCcw = field(kCommandMswBits, "Manual Move CCW");
inline constexpr std::uint16_t kPresetPosition = field(kCommandMswBits, "Preset Position");
inline constexpr std::uint16_t kPresetEncoder = field(kCommandMswBits, "Preset Encoder");
inline constexpr std::uint16_t kResetErrors = field(kCommandMswBits, "Reset Errors");
inline constexpr std::uint16_t kRunBlendCw = field(kCommandMswBits, "Run Blend Move CW");
inline constexpr std::uint16_t kRunBlendCcw = field(kCommandMswBits, "Run Blend Move CCW");
inline constexpr std::uint16_t kConfigMode = field(kCommandMswBits, "Configuration Mode");
inline constexpr std::uint16_t kReserved14 = detail::unnamed(kCommandMswBits);  // A33: -> CE
// Every command bit (0..13): all named bits but the mode bit.
inline constexpr std::uint16_t kCommandMask =
    static_cast<std::uint16_t>(~(kReserved14 | kConfigMode));
}  // namespace cmd_msw

namespace cmd_lsw {
using detail::field;
inline constexpr std::uint16_t kSCurve =
    field(kCommandLswBits, "S-Curve Acceleration (0 = constant)");
// With kSCurve: 0 triangular, 1 trapezoidal.
inline constexpr std::uint16_t kTrapezoidalS =
    field(kCommandLswBits, "Trapezoidal S-Curve (0 = triangular)");
inline constexpr std::uint16_t kEncoderMove = field(kCommandLswBits, "Encoder Move");
inline constexpr std::uint16_t kEncoderFollower = field(kCommandLswBits, "Encoder Follower");
inline constexpr std::uint16_t kProgramBlend = field(kCommandLswBits, "Program Blend Move");
inline constexpr std::uint16_t kBlendTransmit = field(kCommandLswBits, "Blend Move Data Transmit");
inline constexpr std::uint16_t kStoreMinRegistration =
    field(kCommandLswBits, "Store Minimum Registration Distance");
inline constexpr std::uint16_t kBackplaneProximity =
    field(kCommandLswBits, "Backplane Home Proximity");
}  // namespace cmd_lsw

namespace status_msw {
using detail::field;
inline constexpr std::uint16_t kMovingCw = field(kStatusMswBits, "Moving CW");
inline constexpr std::uint16_t kMovingCcw = field(kStatusMswBits, "Moving CCW");
inline constexpr std::uint16_t kHoldState = field(kStatusMswBits, "Hold State");
inline constexpr std::uint16_t kStopped = field(kStatusMswBits, "Stopped");
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
inline constexpr std::uint16_t kModuleOk = field(kStatusMswBits, "Module OK");
inline constexpr std::uint16_t kConfigMode = field(kStatusMswBits, "Configuration Mode");
}  // namespace status_msw

namespace status_lsw {
using detail::field;
inline constexpr std::uint16_t kCaptureActive = field(kStatusLswBits, "Capture Input Active");
inline constexpr std::uint16_t kExternalActive = field(kStatusLswBits, "External Input Active");
inline constexpr std::uint16_t kHomeActive = field(kStatusLswBits, "Home Input Active");
inline constexpr std::uint16_t kEStopActive = field(kStatusLswBits, "E-Stop Input Active");
inline constexpr std::uint16_t kCwLimitActive = field(kStatusLswBits, "CW Limit Active");
inline constexpr std::uint16_t kCcwLimitActive = field(kStatusLswBits, "CCW Limit Active");
inline constexpr std::uint16_t kFollowerMode = field(kStatusLswBits, "Encoder Follower Mode");
inline constexpr std::uint16_t kBlendRunning = field(kStatusLswBits, "Blend Move Running");
inline constexpr std::uint16_t kBlendAcknowledge = field(kStatusLswBits, "Blend Block Acknowledge");
inline constexpr std::uint16_t kMinRegistrationSet =
    field(kStatusLswBits, "Min. Registration Distance Set");
inline constexpr std::uint16_t kProximityEcho =
    field(kStatusLswBits, "Backplane Home Proximity Echo");
}  // namespace status_lsw

// Firmware revision reported in configuration mode (3601 manual ch. 3): the features emulated are
// those of firmware 4.1 (registration move, encoder follower).
inline constexpr std::uint16_t kFirmwareMajor = 4;
inline constexpr std::uint16_t kFirmwareMinor = 1;

}  // namespace stepmod::words::m3601

// ---- the number encoding: decimal (thousands) split, 3601 manual ch. 5 --------------------------
// Words are passed as the sign-extended int32 values of ImageWords; only their low 16 bits count.
namespace stepmod::words {

// value = MSW * 1000 + LSW. Valid when |LSW| <= 999 and the words do not have opposite signs
// (either may be 0). nullopt = the module answers with a Command Error.
std::optional<std::int32_t> decode_3601(std::int32_t msw, std::int32_t lsw) noexcept;
// Parameters that cannot be negative (speeds, Vs, segment length, registration distance):
// MSW >= 0 and LSW 0..999.
std::optional<std::int32_t> decode_3601_unsigned(std::int32_t msw, std::int32_t lsw) noexcept;
// Reported registers (position, encoder, capture): MSW*1000 + LSW without validity rules. A value
// whose thousands wrapped in the MSW (A9) reads back modulo 65,536,000.
std::int64_t decode_3601_report(std::int32_t msw, std::int32_t lsw) noexcept;
// q = trunc(value / 1000) toward zero, r = value - 1000 q; MSW = q wrapped to 16 bits (A9: the
// module reports thousands beyond +-32,767 by letting the MSW wrap, 7FFFh -> 8000h).
WordPair encode_3601(std::int64_t value) noexcept;

}  // namespace stepmod::words

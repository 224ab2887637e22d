#pragma once
// 3601 backplane words and bits, named as in the 3601 manual (shared/spec/manuals/001_...;
// digest MODULES.md section 3). The only place these positions are written down: grep a bit's
// name here to find where it is set.
#include <cstdint>

namespace stepmod::module::m3601 {

inline constexpr unsigned kWords = 8;
inline constexpr std::uint16_t bit(unsigned n) { return static_cast<std::uint16_t>(1u << n); }

// Output words (PLC -> module), both modes.
namespace out_word {
inline constexpr unsigned kMsw = 0;         // config bits MSW / command word MSW
inline constexpr unsigned kLsw = 1;         // config bits LSW / command word LSW
inline constexpr unsigned kTargetMsw = 2;   // config: starting speed MSW
inline constexpr unsigned kTargetLsw = 3;   // config: starting speed LSW
inline constexpr unsigned kSpeedMsw = 4;
inline constexpr unsigned kSpeedLsw = 5;
inline constexpr unsigned kAccel = 6;
inline constexpr unsigned kDecel = 7;
}  // namespace out_word

// Input words (module -> PLC), command mode (digest 3.9).
namespace in_word {
inline constexpr unsigned kStatusMsw = 0;
inline constexpr unsigned kStatusLsw = 1;
inline constexpr unsigned kPositionMsw = 2;
inline constexpr unsigned kPositionLsw = 3;
inline constexpr unsigned kEncoderMsw = 4;
inline constexpr unsigned kEncoderLsw = 5;
inline constexpr unsigned kCaptureMsw = 6;
inline constexpr unsigned kCaptureLsw = 7;
// Configuration mode (digest 3.4): words 0..3 mirror the accepted configuration.
inline constexpr unsigned kFirmwareMajor = 6;
inline constexpr unsigned kFirmwareMinor = 7;
}  // namespace in_word

// Configuration bits MSW (output word 0 in configuration mode, digest 3.2).
namespace cfg_msw {
inline constexpr std::uint16_t kCaptureUsed = bit(0);
inline constexpr std::uint16_t kExternalUsed = bit(1);
inline constexpr std::uint16_t kHomeUsed = bit(2);
inline constexpr std::uint16_t kEStopUsed = bit(3);
inline constexpr std::uint16_t kCwLimitUsed = bit(4);
inline constexpr std::uint16_t kCcwLimitUsed = bit(5);
inline constexpr std::uint16_t kBackplaneProximity = bit(6);
inline constexpr std::uint16_t kQuadratureEncoder = bit(8);
inline constexpr std::uint16_t kDiagnosticFeedback = bit(9);
inline constexpr std::uint16_t kStepDirOutput = bit(10);  // 0 = CW/CCW pulse outputs
inline constexpr std::uint16_t kMarkerHoming = bit(12);   // 0 = home-switch homing
inline constexpr std::uint16_t kConfigMode = bit(15);
inline constexpr std::uint16_t kReserved = bit(7) | bit(11) | bit(13) | bit(14);
}  // namespace cfg_msw

// Configuration bits LSW: active level per input, 1 = active high (digest 3.3). Bit n belongs to
// the input whose "used" bit is bit n of cfg_msw (capture, external, home, E-stop, CW, CCW).
namespace cfg_lsw {
inline constexpr std::uint16_t kReserved = 0xFFC0;  // bits 6..15
}  // namespace cfg_lsw

// Command word MSW (output word 0 in command mode, digest 3.6). Bits 0..13 are commands; at most
// one may be set.
namespace cmd_msw {
inline constexpr std::uint16_t kAbsoluteMove = bit(0);
inline constexpr std::uint16_t kRelativeMove = bit(1);
inline constexpr std::uint16_t kHold = bit(2);
inline constexpr std::uint16_t kResume = bit(3);
inline constexpr std::uint16_t kImmediateStop = bit(4);
inline constexpr std::uint16_t kFindHomeCw = bit(5);
inline constexpr std::uint16_t kFindHomeCcw = bit(6);
inline constexpr std::uint16_t kManualCw = bit(7);   // level; also follower "same sense"
inline constexpr std::uint16_t kManualCcw = bit(8);  // level; also follower "reverse"
inline constexpr std::uint16_t kPresetPosition = bit(9);
inline constexpr std::uint16_t kPresetEncoder = bit(10);
inline constexpr std::uint16_t kResetErrors = bit(11);
inline constexpr std::uint16_t kRunBlendCw = bit(12);
inline constexpr std::uint16_t kRunBlendCcw = bit(13);
inline constexpr std::uint16_t kReserved14 = bit(14);  // A33: set with a command -> CE
inline constexpr std::uint16_t kConfigMode = bit(15);
inline constexpr std::uint16_t kCommandMask = 0x3FFF;
}  // namespace cmd_msw

// Command word LSW (output word 1 in command mode, digest 3.7).
namespace cmd_lsw {
inline constexpr std::uint16_t kSCurve = bit(0);         // 0 = constant acceleration
inline constexpr std::uint16_t kTrapezoidalS = bit(1);   // with kSCurve: 0 triangular, 1 trapezoidal
inline constexpr std::uint16_t kEncoderMove = bit(2);
inline constexpr std::uint16_t kEncoderFollower = bit(7);
inline constexpr std::uint16_t kProgramBlend = bit(8);
inline constexpr std::uint16_t kBlendTransmit = bit(9);
inline constexpr std::uint16_t kStoreMinRegistration = bit(10);
inline constexpr std::uint16_t kBackplaneProximity = bit(12);
}  // namespace cmd_lsw

// Status word MSW (input word 0, digest 3.10).
namespace status_msw {
inline constexpr std::uint16_t kMovingCw = bit(0);
inline constexpr std::uint16_t kMovingCcw = bit(1);
inline constexpr std::uint16_t kHoldState = bit(2);
inline constexpr std::uint16_t kStopped = bit(3);
inline constexpr std::uint16_t kAtHome = bit(4);
inline constexpr std::uint16_t kAccelerating = bit(5);
inline constexpr std::uint16_t kDecelerating = bit(6);
inline constexpr std::uint16_t kMoveComplete = bit(7);
inline constexpr std::uint16_t kHomeInvalid = bit(8);
inline constexpr std::uint16_t kInvalidProfile = bit(9);
inline constexpr std::uint16_t kPositionInvalid = bit(10);
inline constexpr std::uint16_t kInputError = bit(11);
inline constexpr std::uint16_t kCommandError = bit(12);
inline constexpr std::uint16_t kConfigurationError = bit(13);
inline constexpr std::uint16_t kModuleOk = bit(14);
inline constexpr std::uint16_t kConfigMode = bit(15);
}  // namespace status_msw

// Status word LSW (input word 1, digest 3.11). Bits 0..5: logical input states, in the order of
// the configuration bits (capture, external, home, E-stop, CW limit, CCW limit).
namespace status_lsw {
inline constexpr std::uint16_t kCaptureActive = bit(0);
inline constexpr std::uint16_t kExternalActive = bit(1);
inline constexpr std::uint16_t kHomeActive = bit(2);
inline constexpr std::uint16_t kEStopActive = bit(3);
inline constexpr std::uint16_t kCwLimitActive = bit(4);
inline constexpr std::uint16_t kCcwLimitActive = bit(5);
inline constexpr std::uint16_t kFollowerMode = bit(7);
inline constexpr std::uint16_t kBlendRunning = bit(8);
inline constexpr std::uint16_t kBlendAcknowledge = bit(9);
inline constexpr std::uint16_t kMinRegistrationSet = bit(10);
inline constexpr std::uint16_t kProximityEcho = bit(12);
}  // namespace status_lsw

// Firmware revision reported in configuration mode (digest 3.4): the features emulated are those
// of firmware 4.1 (registration move, encoder follower).
inline constexpr std::uint16_t kFirmwareMajor = 4;
inline constexpr std::uint16_t kFirmwareMinor = 1;

}  // namespace stepmod::module::m3601

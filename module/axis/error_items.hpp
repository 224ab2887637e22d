#pragma once
// The conditions the shared axis code reports with a reason, each with its item number in the
// 3601, 3602 and 3202 checklists (error_reason.hpp). One place, so that docs/error-reasons.md is
// generated from it (tests/module/error_reason_test.cpp checks the file) and a search for an
// item name finds the line that raises it.
#include <array>

#include "module/axis/error_reason.hpp"

namespace stepmod::module::axis::items {

using L = ErrorList;

// ---- Configuration Error (the dialects' configuration checks add their own: config_*.cpp) ----
inline constexpr Item kConfigInvalid{L::kConfiguration, {0, 0, 0}, "the configuration words"};
inline constexpr Item kPowerUp{L::kConfiguration, {1, 1, 0}, "not configured since power-up"};

// ---- Command Error ----
// The manuals only say a module "has to be configured before starting any operations"; the
// Command Error is stepmod's answer, so the item is its own (S2).
inline constexpr Item kNotConfigured{
    L::kCommand, {92, 92, 92}, "a command before configuration (stepmod)"};
inline constexpr Item kConfigWhileMoving{
    L::kCommand, {1, 1, 1}, "configuration mode requested while moving"};
inline constexpr Item kSeveralCommands{L::kCommand, {2, 2, 2}, "more than one command bit set"};
inline constexpr Item kUndefinedCommand{L::kCommand, {2, 2, 24}, "an undefined command bit set"};
// The 3202 states it (manual Ch.4, the moves' note 2) without a number in its list: S3.
inline constexpr Item kMoveWhileMoving{
    L::kCommand, {3, 4, 93}, "a move while another motion is running"};
inline constexpr Item kWordsNotZero{
    L::kCommand, {15, 10, 9}, "command words that must be 0 are not"};
inline constexpr Item kReservedWords{L::kCommand, {0, 10, 5}, "reserved command words not 0"};
inline constexpr Item kOutOfRange{
    L::kCommand, {4, 5, 3}, "target, speed, accel or decel out of range"};
inline constexpr Item kVpBelowVs{L::kCommand, {5, 6, 4}, "programmed speed below starting speed"};
inline constexpr Item kAbsoluteWithPi{
    L::kCommand, {6, 7, 6}, "absolute move with the position invalid"};
inline constexpr Item kHoldNotHoldable{
    L::kCommand, {7, 8, 7}, "Hold without an absolute/relative move"};
inline constexpr Item kResumeNotHeld{L::kCommand, {8, 9, 8}, "Resume when not in Hold"};
inline constexpr Item kHomeSCurve{L::kCommand, {10, 11, 10}, "Find Home with S-curve"};
inline constexpr Item kHomeNoLimit{
    L::kCommand, {13, 0, 22}, "Find Home toward no configured end limit"};
// Find Home with a target: the 3602's reserved words (CE-10, HI-04 also); the 3601's and 3202's
// Home Invalid item (3601-HI-02, 3202-HI-01; A8: Command Error as well). homing.cpp records the
// one this module's lists number (numbered()).
inline constexpr Item kHomeTarget{L::kCommand, {0, 10, 0}, "Find Home with a target not 0 (3602)"};
inline constexpr Item kHomeTargetHi{
    L::kHomeInvalid, {2, 0, 1}, "Find Home with a target not 0 (3601, 3202)"};
inline constexpr Item kHomeNoInput{L::kCommand, {0, 12, 0}, "Find Home without the home input"};
inline constexpr Item kNoEncoder{
    L::kCommand, {14, 0, 23}, "encoder move with no encoder configured"};
inline constexpr Item kPresetEncoderNoEncoder{
    L::kCommand, {11, 0, 11}, "Preset Encoder with no encoder configured"};
// Registration and blend: the 3602's lettered items (R1.., B1..: error_reason.hpp).
inline constexpr Item kMinRegRange{
    L::kCommand, {25, 81, 0}, "minimum registration distance out of range"};
inline constexpr Item kRegExternal{
    L::kCommand, {27, 83, 0}, "registration move with External active"};
inline constexpr Item kRegTooShort{
    L::kCommand, {28, 84, 0}, "registration steps fewer than to stop"};
inline constexpr Item kRegNegative{L::kCommand, {29, 85, 0}, "a negative registration count"};
inline constexpr Item kJogWithTarget{L::kCommand, {0, 0, 12}, "a manual move with a target not 0"};
// A manual (jog) or registration move changed while it runs: motion stops (J1.., R6..).
inline constexpr Item kJogConstantSpeed{
    L::kCommand, {17, 71, 15}, "a speed change on a constant-speed jog"};
inline constexpr Item kJogInvalidChange{
    L::kCommand, {19, 72, 16}, "an invalid speed, accel or decel in a jog"};
inline constexpr Item kJogSpeedZero{L::kCommand, {19, 72, 14}, "a jog's speed changed to 0"};
inline constexpr Item kJogTargetWritten{
    L::kCommand, {30, 73, 13}, "a target written while a jog runs"};
inline constexpr Item kRegCountChanged{
    L::kCommand, {31, 86, 0}, "registration count changed after the start"};
inline constexpr Item kRegSpeedIncreased{
    L::kCommand, {32, 87, 0}, "a registration move's speed increased"};
inline constexpr Item kRegRatesChanged{
    L::kCommand, {33, 88, 0}, "registration accel or decel changed"};
inline constexpr Item kBlendNotStored{
    L::kCommand, {20, 51, 17}, "Run Blend with no profile stored"};
inline constexpr Item kBlendWhileBlending{
    L::kCommand, {22, 54, 19}, "blend programming while a blend runs"};
inline constexpr Item kHoldDuringBlend{L::kCommand, {23, 8, 20}, "Hold during a blend"};
inline constexpr Item kFollowerNoEncoder{
    L::kCommand, {34, 0, 0}, "follower mode with no encoder configured"};
inline constexpr Item kFollowerWhileMoving{
    L::kCommand, {35, 0, 0}, "follower mode while a motion runs"};
inline constexpr Item kFollowerRatio{L::kCommand, {36, 0, 0}, "follower ratio out of 1..32767"};
inline constexpr Item kFollowerSpeed{L::kCommand, {37, 0, 0}, "follower with speed words not 0"};
inline constexpr Item kFollowerDirection{
    L::kCommand, {38, 0, 0}, "follower direction changed with no 0 scan"};
inline constexpr Item kFollowerOtherCommand{
    L::kCommand, {39, 0, 0}, "a command other than +/- in follower mode"};
inline constexpr Item kFollowerReleased{
    L::kCommand, {40, 0, 0}, "follower flag cleared with a direction set"};
inline constexpr Item kFollowerSCurve{L::kCommand, {41, 0, 0}, "S-curve with the follower"};
inline constexpr Item kFollowerLimit{
    L::kCommand, {42, 0, 0}, "follower mode with an end limit active"};
inline constexpr Item kPlannerFull{
    L::kCommand, {91, 91, 91}, "the planner's queue is full (stepmod)"};

// ---- Invalid Profile ----
inline constexpr Item kProfileVpBelowVs{
    L::kInvalidProfile, {1, 1, 1}, "programmed speed below starting speed"};
inline constexpr Item kProfileOutOfRange{
    L::kInvalidProfile, {2, 2, 2}, "a move parameter out of range"};
inline constexpr Item kProfileOverflow{
    L::kInvalidProfile, {3, 3, 4}, "the profile overflows 32-bit registers"};
inline constexpr Item kProfileReserved{L::kInvalidProfile, {0, 18, 3}, "reserved words not 0"};
inline constexpr Item kBlendSegmentCount{
    L::kInvalidProfile, {4, 4, 12}, "blend segment count not 2..16"};
inline constexpr Item kBlendNoFinalDecel{
    L::kInvalidProfile, {7, 0, 17}, "blend profile without a final deceleration"};
inline constexpr Item kBlendBlockError{
    L::kInvalidProfile, {21, 19, 0}, "an error in a blend programming block"};
inline constexpr Item kBlendNotConfigured{
    L::kInvalidProfile, {0, 0, 15}, "blend message to an unconfigured channel"};
inline constexpr Item kBlendNoChannel{
    L::kInvalidProfile, {0, 0, 11}, "blend message channel not 1 or 2"};

// ---- Input Error ----
inline constexpr Item kEStop{L::kInput, {1, 1, 1}, "the E-stop input activated"};
inline constexpr Item kLimitInMove{L::kInput, {2, 2, 2}, "an end limit reached during a move"};
inline constexpr Item kStartTowardLimit{
    L::kInput, {3, 5, 3}, "a start toward an active limit or E-stop"};
inline constexpr Item kHomingSecondLimit{
    L::kInput, {4, 0, 4}, "homing met the other limit after reversing"};
inline constexpr Item kHomingOppositeLimit{
    L::kInput, {5, 4, 5}, "homing reached the opposite limit first"};

// ---- Home Invalid ----
inline constexpr Item kHomeFailed{L::kHomeInvalid, {0, 0, 0}, "homing did not find home"};
inline constexpr Item kHomeLimitError{
    L::kHomeInvalid, {5, 5, 6}, "homing met the opposite or a second limit"};
inline constexpr Item kHomeTimeout{L::kHomeInvalid, {0, 7, 0}, "homing timeout expired"};

// ---- Position Invalid ----
inline constexpr Item kPiConfigured{
    L::kPositionInvalid, {1, 1, 1}, "a configuration (the position is 0)"};
inline constexpr Item kPiImmediateStop{
    L::kPositionInvalid, {2, 2, 2}, "Immediate Stop while moving"};
inline constexpr Item kPiEStop{L::kPositionInvalid, {3, 3, 3}, "E-stop while moving"};
inline constexpr Item kPiLimit{L::kPositionInvalid, {4, 4, 4}, "an end limit during a move"};
inline constexpr Item kPiPlcStopped{
    L::kPositionInvalid, {7, 0, 8}, "the PLC left Run mode while moving"};
inline constexpr Item kPiLateEdge{
    L::kPositionInvalid, {91, 91, 91}, "a late-edge fault stopped it (stepmod)"};
inline constexpr Item kPiLeaseExpired{
    L::kPositionInvalid, {92, 92, 92}, "commissioning lease expired (stepmod)"};
inline constexpr Item kPiInputLost{
    L::kPositionInvalid, {93, 93, 93}, "an input edge was lost (stepmod)"};
inline constexpr Item kPiFault{L::kPositionInvalid, {0, 0, 0}, "a fault stopped the axis"};

// Of two items for one condition in different lists, the one module `t` numbers (`a` first).
inline const Item& numbered(const Item& a, const Item& b, ModuleType t) noexcept {
  return a.number(t) != 0 ? a : b;
}

// Every item above, for the documentation table.
inline constexpr std::array kAll{&kConfigInvalid,
                                 &kPowerUp,
                                 &kNotConfigured,
                                 &kConfigWhileMoving,
                                 &kSeveralCommands,
                                 &kUndefinedCommand,
                                 &kMoveWhileMoving,
                                 &kWordsNotZero,
                                 &kReservedWords,
                                 &kOutOfRange,
                                 &kVpBelowVs,
                                 &kAbsoluteWithPi,
                                 &kHoldNotHoldable,
                                 &kResumeNotHeld,
                                 &kHomeSCurve,
                                 &kHomeNoLimit,
                                 &kHomeTarget,
                                 &kHomeTargetHi,
                                 &kHomeNoInput,
                                 &kNoEncoder,
                                 &kPresetEncoderNoEncoder,
                                 &kMinRegRange,
                                 &kRegExternal,
                                 &kRegTooShort,
                                 &kRegNegative,
                                 &kJogWithTarget,
                                 &kJogConstantSpeed,
                                 &kJogInvalidChange,
                                 &kJogSpeedZero,
                                 &kJogTargetWritten,
                                 &kRegCountChanged,
                                 &kRegSpeedIncreased,
                                 &kRegRatesChanged,
                                 &kBlendNotStored,
                                 &kBlendWhileBlending,
                                 &kHoldDuringBlend,
                                 &kFollowerNoEncoder,
                                 &kFollowerWhileMoving,
                                 &kFollowerRatio,
                                 &kFollowerSpeed,
                                 &kFollowerDirection,
                                 &kFollowerOtherCommand,
                                 &kFollowerReleased,
                                 &kFollowerSCurve,
                                 &kFollowerLimit,
                                 &kPlannerFull,
                                 &kProfileOverflow,
                                 &kProfileVpBelowVs,
                                 &kProfileOutOfRange,
                                 &kProfileReserved,
                                 &kBlendSegmentCount,
                                 &kBlendNoFinalDecel,
                                 &kBlendBlockError,
                                 &kBlendNotConfigured,
                                 &kBlendNoChannel,
                                 &kEStop,
                                 &kLimitInMove,
                                 &kStartTowardLimit,
                                 &kHomingSecondLimit,
                                 &kHomingOppositeLimit,
                                 &kHomeFailed,
                                 &kHomeLimitError,
                                 &kHomeTimeout,
                                 &kPiConfigured,
                                 &kPiImmediateStop,
                                 &kPiEStop,
                                 &kPiLimit,
                                 &kPiPlcStopped,
                                 &kPiLateEdge,
                                 &kPiLeaseExpired,
                                 &kPiInputLost,
                                 &kPiFault};

}  // namespace stepmod::module::axis::items

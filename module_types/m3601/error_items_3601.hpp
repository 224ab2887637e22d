#pragma once
// The 3601's numbers of the shared axis code's conditions (module/axis/error_items.hpp) in its
// checklists (the 3601 manual's error lists; error_reason.hpp numbers the lettered and stepmod's
// own items): the 3601's column of docs/error-reasons.md. A condition not named here has no item
// in its lists (0: the reason names the list only).
#include "module/axis/item_ids.hpp"

namespace stepmod::module::m3601 {

inline constexpr axis::ItemNumber kErrorItemNumbers[] = {
    {axis::ItemId::kPowerUp, 1},
    {axis::ItemId::kNotConfigured, 92},
    {axis::ItemId::kConfigWhileMoving, 1},
    {axis::ItemId::kSeveralCommands, 2},
    {axis::ItemId::kUndefinedCommand, 2},
    {axis::ItemId::kMoveWhileMoving, 3},
    {axis::ItemId::kWordsNotZero, 15},
    {axis::ItemId::kOutOfRange, 4},
    {axis::ItemId::kVpBelowVs, 5},
    {axis::ItemId::kAbsoluteWithPi, 6},
    {axis::ItemId::kHoldNotHoldable, 7},
    {axis::ItemId::kResumeNotHeld, 8},
    {axis::ItemId::kHomeSCurve, 10},
    {axis::ItemId::kHomeNoLimit, 13},
    {axis::ItemId::kHomeTargetHi, 2},
    {axis::ItemId::kNoEncoder, 14},
    {axis::ItemId::kPresetEncoderNoEncoder, 11},
    {axis::ItemId::kMinRegRange, 25},
    {axis::ItemId::kRegExternal, 27},
    {axis::ItemId::kRegTooShort, 28},
    {axis::ItemId::kRegNegative, 29},
    {axis::ItemId::kJogConstantSpeed, 17},
    {axis::ItemId::kJogInvalidChange, 19},
    {axis::ItemId::kJogSpeedZero, 19},
    {axis::ItemId::kJogTargetWritten, 30},
    {axis::ItemId::kRegCountChanged, 31},
    {axis::ItemId::kRegSpeedIncreased, 32},
    {axis::ItemId::kRegRatesChanged, 33},
    {axis::ItemId::kBlendNotStored, 20},
    {axis::ItemId::kBlendWhileBlending, 22},
    {axis::ItemId::kHoldDuringBlend, 23},
    {axis::ItemId::kFollowerNoEncoder, 34},
    {axis::ItemId::kFollowerWhileMoving, 35},
    {axis::ItemId::kFollowerRatio, 36},
    {axis::ItemId::kFollowerSpeed, 37},
    {axis::ItemId::kFollowerDirection, 38},
    {axis::ItemId::kFollowerOtherCommand, 39},
    {axis::ItemId::kFollowerReleased, 40},
    {axis::ItemId::kFollowerSCurve, 41},
    {axis::ItemId::kFollowerLimit, 42},
    {axis::ItemId::kPlannerFull, 91},
    {axis::ItemId::kProfileVpBelowVs, 1},
    {axis::ItemId::kProfileOutOfRange, 2},
    {axis::ItemId::kProfileOverflow, 3},
    {axis::ItemId::kBlendSegmentCount, 4},
    {axis::ItemId::kBlendNoFinalDecel, 7},
    {axis::ItemId::kBlendBlockError, 21},
    {axis::ItemId::kEStop, 1},
    {axis::ItemId::kLimitInMove, 2},
    {axis::ItemId::kStartTowardLimit, 3},
    {axis::ItemId::kHomingSecondLimit, 4},
    {axis::ItemId::kHomingOppositeLimit, 5},
    {axis::ItemId::kHomeLimitError, 5},
    {axis::ItemId::kPiConfigured, 1},
    {axis::ItemId::kPiImmediateStop, 2},
    {axis::ItemId::kPiEStop, 3},
    {axis::ItemId::kPiLimit, 4},
    {axis::ItemId::kPiPlcStopped, 7},
    {axis::ItemId::kPiLateEdge, 91},
    {axis::ItemId::kPiLeaseExpired, 92},
    {axis::ItemId::kPiInputLost, 93},
};
inline constexpr axis::ItemColumn kErrorItems =
    axis::item_column(ModuleType::k3601, kErrorItemNumbers);

}  // namespace stepmod::module::m3601

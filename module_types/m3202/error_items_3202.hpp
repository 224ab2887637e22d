#pragma once
// The 3202's numbers of the shared axis code's conditions (module/axis/error_items.hpp) in its
// checklists (the 3202 manual's error lists; error_reason.hpp numbers the lettered and stepmod's
// own items): the 3202's column of docs/error-reasons.md. A condition not named here has no item
// in its lists (0: the reason names the list only).
#include "module/axis/item_ids.hpp"

namespace stepmod::module::m3202 {

inline constexpr axis::ItemNumber kErrorItemNumbers[] = {
    {axis::ItemId::kNotConfigured, 92},
    {axis::ItemId::kConfigWhileMoving, 1},
    {axis::ItemId::kSeveralCommands, 2},
    {axis::ItemId::kUndefinedCommand, 24},
    {axis::ItemId::kMoveWhileMoving, 93},
    {axis::ItemId::kWordsNotZero, 9},
    {axis::ItemId::kReservedWords, 5},
    {axis::ItemId::kOutOfRange, 3},
    {axis::ItemId::kVpBelowVs, 4},
    {axis::ItemId::kAbsoluteWithPi, 6},
    {axis::ItemId::kHoldNotHoldable, 7},
    {axis::ItemId::kResumeNotHeld, 8},
    {axis::ItemId::kHomeSCurve, 10},
    {axis::ItemId::kHomeNoLimit, 22},
    {axis::ItemId::kHomeTargetHi, 1},
    {axis::ItemId::kNoEncoder, 23},
    {axis::ItemId::kPresetEncoderNoEncoder, 11},
    {axis::ItemId::kJogWithTarget, 12},
    {axis::ItemId::kJogConstantSpeed, 15},
    {axis::ItemId::kJogInvalidChange, 16},
    {axis::ItemId::kJogSpeedZero, 14},
    {axis::ItemId::kJogTargetWritten, 13},
    {axis::ItemId::kBlendNotStored, 17},
    {axis::ItemId::kBlendWhileBlending, 19},
    {axis::ItemId::kHoldDuringBlend, 20},
    {axis::ItemId::kPlannerFull, 91},
    {axis::ItemId::kProfileVpBelowVs, 1},
    {axis::ItemId::kProfileOutOfRange, 2},
    {axis::ItemId::kProfileOverflow, 4},
    {axis::ItemId::kProfileReserved, 3},
    {axis::ItemId::kBlendSegmentCount, 12},
    {axis::ItemId::kBlendNoFinalDecel, 17},
    {axis::ItemId::kBlendNotConfigured, 15},
    {axis::ItemId::kBlendNoChannel, 11},
    {axis::ItemId::kEStop, 1},
    {axis::ItemId::kLimitInMove, 2},
    {axis::ItemId::kStartTowardLimit, 3},
    {axis::ItemId::kHomingSecondLimit, 4},
    {axis::ItemId::kHomingOppositeLimit, 5},
    {axis::ItemId::kHomeLimitError, 6},
    {axis::ItemId::kPiConfigured, 1},
    {axis::ItemId::kPiImmediateStop, 2},
    {axis::ItemId::kPiEStop, 3},
    {axis::ItemId::kPiLimit, 4},
    {axis::ItemId::kPiPlcStopped, 8},
    {axis::ItemId::kPiLateEdge, 91},
    {axis::ItemId::kPiLeaseExpired, 92},
    {axis::ItemId::kPiInputLost, 93},
};
inline constexpr axis::ItemColumn kErrorItems =
    axis::item_column(ModuleType::k3202, kErrorItemNumbers);

}  // namespace stepmod::module::m3202

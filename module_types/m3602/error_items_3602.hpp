#pragma once
// The 3602's numbers of the shared axis code's conditions (module/axis/error_items.hpp) in its
// checklists (the 3602 manual's error lists; error_reason.hpp numbers the lettered and stepmod's
// own items): the 3602's column of docs/error-reasons.md. A condition not named here has no item
// in its lists (0: the reason names the list only).
#include "module/axis/item_ids.hpp"

namespace stepmod::module::m3602 {

inline constexpr axis::ItemNumber kErrorItemNumbers[] = {
    {axis::ItemId::kPowerUp, 1},
    {axis::ItemId::kNotConfigured, 92},
    {axis::ItemId::kConfigWhileMoving, 1},
    {axis::ItemId::kSeveralCommands, 2},
    {axis::ItemId::kUndefinedCommand, 2},
    {axis::ItemId::kMoveWhileMoving, 4},
    {axis::ItemId::kWordsNotZero, 10},
    {axis::ItemId::kReservedWords, 10},
    {axis::ItemId::kOutOfRange, 5},
    {axis::ItemId::kVpBelowVs, 6},
    {axis::ItemId::kAbsoluteWithPi, 7},
    {axis::ItemId::kHoldNotHoldable, 8},
    {axis::ItemId::kResumeNotHeld, 9},
    {axis::ItemId::kHomeSCurve, 11},
    {axis::ItemId::kHomeTarget, 10},
    {axis::ItemId::kHomeNoInput, 12},
    {axis::ItemId::kMinRegRange, 81},
    {axis::ItemId::kRegExternal, 83},
    {axis::ItemId::kRegTooShort, 84},
    {axis::ItemId::kRegNegative, 85},
    {axis::ItemId::kJogConstantSpeed, 71},
    {axis::ItemId::kJogInvalidChange, 72},
    {axis::ItemId::kJogSpeedZero, 72},
    {axis::ItemId::kJogTargetWritten, 73},
    {axis::ItemId::kRegCountChanged, 86},
    {axis::ItemId::kRegSpeedIncreased, 87},
    {axis::ItemId::kRegRatesChanged, 88},
    {axis::ItemId::kBlendNotStored, 51},
    {axis::ItemId::kBlendWhileBlending, 54},
    {axis::ItemId::kHoldDuringBlend, 8},
    {axis::ItemId::kPlannerFull, 91},
    {axis::ItemId::kProfileVpBelowVs, 1},
    {axis::ItemId::kProfileOutOfRange, 2},
    {axis::ItemId::kProfileOverflow, 3},
    {axis::ItemId::kProfileReserved, 18},
    {axis::ItemId::kBlendSegmentCount, 4},
    {axis::ItemId::kBlendBlockError, 19},
    {axis::ItemId::kEStop, 1},
    {axis::ItemId::kLimitInMove, 2},
    {axis::ItemId::kStartTowardLimit, 5},
    {axis::ItemId::kHomingOppositeLimit, 4},
    {axis::ItemId::kHomeLimitError, 5},
    {axis::ItemId::kHomeTimeout, 7},
    {axis::ItemId::kPiConfigured, 1},
    {axis::ItemId::kPiImmediateStop, 2},
    {axis::ItemId::kPiEStop, 3},
    {axis::ItemId::kPiLimit, 4},
    {axis::ItemId::kPiLateEdge, 91},
    {axis::ItemId::kPiLeaseExpired, 92},
    {axis::ItemId::kPiInputLost, 93},
};
inline constexpr axis::ItemColumn kErrorItems =
    axis::item_column(ModuleType::k3602, kErrorItemNumbers);

}  // namespace stepmod::module::m3602

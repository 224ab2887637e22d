#pragma once
// The conditions of the shared axis code (error_items.hpp) by name: the key of each module type's
// column of checklist numbers (module_types/mXXXX/error_items_XXXX.hpp), so that a module type's
// numbers live in its own folder and error_items.hpp names each condition once, for every module.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "core/module_shape.hpp"

namespace stepmod::module::axis {

// One per Item of error_items.hpp, in its order.
enum class ItemId : std::uint8_t {
  kConfigInvalid,
  kPowerUp,
  kNotConfigured,
  kConfigWhileMoving,
  kSeveralCommands,
  kUndefinedCommand,
  kMoveWhileMoving,
  kWordsNotZero,
  kReservedWords,
  kOutOfRange,
  kVpBelowVs,
  kAbsoluteWithPi,
  kHoldNotHoldable,
  kResumeNotHeld,
  kHomeSCurve,
  kHomeNoLimit,
  kHomeTarget,
  kHomeTargetHi,
  kHomeNoInput,
  kNoEncoder,
  kPresetEncoderNoEncoder,
  kMinRegRange,
  kRegExternal,
  kRegTooShort,
  kRegNegative,
  kJogWithTarget,
  kJogConstantSpeed,
  kJogInvalidChange,
  kJogSpeedZero,
  kJogTargetWritten,
  kRegCountChanged,
  kRegSpeedIncreased,
  kRegRatesChanged,
  kBlendNotStored,
  kBlendWhileBlending,
  kHoldDuringBlend,
  kFollowerNoEncoder,
  kFollowerWhileMoving,
  kFollowerRatio,
  kFollowerSpeed,
  kFollowerDirection,
  kFollowerOtherCommand,
  kFollowerReleased,
  kFollowerSCurve,
  kFollowerLimit,
  kPlannerFull,
  kProfileVpBelowVs,
  kProfileOutOfRange,
  kProfileOverflow,
  kProfileReserved,
  kBlendSegmentCount,
  kBlendNoFinalDecel,
  kBlendBlockError,
  kBlendNotConfigured,
  kBlendNoChannel,
  kEStop,
  kLimitInMove,
  kStartTowardLimit,
  kHomingSecondLimit,
  kHomingOppositeLimit,
  kHomeFailed,
  kHomeLimitError,
  kHomeTimeout,
  kPiConfigured,
  kPiImmediateStop,
  kPiEStop,
  kPiLimit,
  kPiPlcStopped,
  kPiLateEdge,
  kPiLeaseExpired,
  kPiInputLost,
  kPiFault,
  kCount
};

inline constexpr std::size_t kItemCount = static_cast<std::size_t>(ItemId::kCount);

// A module type's number of each condition in its checklists (0: its lists have no item for it,
// the reason names the list only).
struct ItemColumn {
  ModuleType type;
  std::array<std::uint8_t, kItemCount> numbers{};
};

struct ItemNumber {
  ItemId id;
  std::uint8_t number;
};

// The column of `type` from the conditions it numbers; the others are 0. A condition named twice
// is a compile-time error (the throw makes the constant expression fail).
constexpr ItemColumn item_column(ModuleType type, std::span<const ItemNumber> numbered) {
  ItemColumn c{type, {}};
  for (const ItemNumber& n : numbered) {
    std::uint8_t& slot = c.numbers[static_cast<std::size_t>(n.id)];
    if (slot != 0 || n.number == 0) throw "item_column: a condition named twice or numbered 0";
    slot = n.number;
  }
  return c;
}

}  // namespace stepmod::module::axis

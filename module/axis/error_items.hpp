#pragma once
// The conditions the shared axis code reports with a reason, each named once here; each module
// type numbers them in its own checklists, in its own folder (module_types/mXXXX/
// error_items_XXXX.hpp, collected by the generated module_types/error_item_columns.hpp). One place
// per condition, so that docs/error-reasons.md is generated from it
// (tests/module/error_reasons_doc_test.cpp checks the file) and a search for an item name finds
// the line that raises it.
#include <array>
#include <cstddef>
#include <cstdint>

#include "module/axis/error_reason.hpp"
#include "module/axis/item_ids.hpp"
#include "module_types/error_item_columns.hpp"

namespace stepmod::module::axis::items {

using L = ErrorList;
using Id = ItemId;

// The numbers of condition `id` in every module type's lists, in kModuleShapes' order (an
// Item's numbers), from each type's column.
constexpr std::array<std::uint8_t, kModuleShapes.size()> numbers_of(ItemId id) {
  std::array<std::uint8_t, kModuleShapes.size()> n{};
  for (std::size_t i = 0; i < n.size(); ++i) {
    for (const ItemColumn* c : module_types::kErrorItemColumns) {
      if (c->type == kModuleShapes[i].type) n[i] = c->numbers[static_cast<std::size_t>(id)];
    }
  }
  return n;
}

constexpr bool every_module_has_a_column() {
  if (module_types::kErrorItemColumns.size() != kModuleShapes.size()) return false;
  for (const ModuleShape& s : kModuleShapes) {
    bool found = false;
    for (const ItemColumn* c : module_types::kErrorItemColumns) found = found || c->type == s.type;
    if (!found) return false;
  }
  return true;
}
static_assert(every_module_has_a_column(), "each module type numbers the conditions in its folder");

// ---- Configuration Error (the dialects' configuration checks add their own: config_*.cpp) ----
inline constexpr Item kConfigInvalid{L::kConfiguration, numbers_of(Id::kConfigInvalid),
                                     "the configuration words"};
inline constexpr Item kPowerUp{L::kConfiguration, numbers_of(Id::kPowerUp),
                               "not configured since power-up"};

// ---- Command Error ----
// The manuals only say a module "has to be configured before starting any operations"; the
// Command Error is stepmod's answer, so the item is its own (S2).
inline constexpr Item kNotConfigured{L::kCommand, numbers_of(Id::kNotConfigured),
                                     "a command before configuration (stepmod)"};
inline constexpr Item kConfigWhileMoving{L::kCommand, numbers_of(Id::kConfigWhileMoving),
                                         "configuration mode requested while moving"};
inline constexpr Item kSeveralCommands{L::kCommand, numbers_of(Id::kSeveralCommands),
                                       "more than one command bit set"};
inline constexpr Item kUndefinedCommand{L::kCommand, numbers_of(Id::kUndefinedCommand),
                                        "an undefined command bit set"};
// The 3202 states it (manual Ch.4, the moves' note 2) without a number in its list: S3.
inline constexpr Item kMoveWhileMoving{L::kCommand, numbers_of(Id::kMoveWhileMoving),
                                       "a move while another motion is running"};
inline constexpr Item kWordsNotZero{L::kCommand, numbers_of(Id::kWordsNotZero),
                                    "command words that must be 0 are not"};
inline constexpr Item kReservedWords{L::kCommand, numbers_of(Id::kReservedWords),
                                     "reserved command words not 0"};
inline constexpr Item kOutOfRange{L::kCommand, numbers_of(Id::kOutOfRange),
                                  "target, speed, accel or decel out of range"};
inline constexpr Item kVpBelowVs{L::kCommand, numbers_of(Id::kVpBelowVs),
                                 "programmed speed below starting speed"};
inline constexpr Item kAbsoluteWithPi{L::kCommand, numbers_of(Id::kAbsoluteWithPi),
                                      "absolute move with the position invalid"};
inline constexpr Item kHoldNotHoldable{L::kCommand, numbers_of(Id::kHoldNotHoldable),
                                       "Hold without an absolute/relative move"};
inline constexpr Item kResumeNotHeld{L::kCommand, numbers_of(Id::kResumeNotHeld),
                                     "Resume when not in Hold"};
inline constexpr Item kHomeSCurve{L::kCommand, numbers_of(Id::kHomeSCurve),
                                  "Find Home with S-curve"};
inline constexpr Item kHomeNoLimit{L::kCommand, numbers_of(Id::kHomeNoLimit),
                                   "Find Home toward no configured end limit"};
// Find Home with a target: the 3602's reserved words (CE-10, HI-04 also); the 3601's and 3202's
// Home Invalid item (3601-HI-02, 3202-HI-01; A8: Command Error as well). homing.cpp records the
// one this module's lists number (numbered()).
inline constexpr Item kHomeTarget{L::kCommand, numbers_of(Id::kHomeTarget),
                                  "Find Home with a target not 0 (3602)"};
inline constexpr Item kHomeTargetHi{L::kHomeInvalid, numbers_of(Id::kHomeTargetHi),
                                    "Find Home with a target not 0 (3601, 3202)"};
inline constexpr Item kHomeNoInput{L::kCommand, numbers_of(Id::kHomeNoInput),
                                   "Find Home without the home input"};
inline constexpr Item kNoEncoder{L::kCommand, numbers_of(Id::kNoEncoder),
                                 "encoder move with no encoder configured"};
inline constexpr Item kPresetEncoderNoEncoder{L::kCommand, numbers_of(Id::kPresetEncoderNoEncoder),
                                              "Preset Encoder with no encoder configured"};
// Registration and blend: the 3602's lettered items (R1.., B1..: error_reason.hpp).
inline constexpr Item kMinRegRange{L::kCommand, numbers_of(Id::kMinRegRange),
                                   "minimum registration distance out of range"};
inline constexpr Item kRegExternal{L::kCommand, numbers_of(Id::kRegExternal),
                                   "registration move with External active"};
inline constexpr Item kRegTooShort{L::kCommand, numbers_of(Id::kRegTooShort),
                                   "registration steps fewer than to stop"};
inline constexpr Item kRegNegative{L::kCommand, numbers_of(Id::kRegNegative),
                                   "a negative registration count"};
inline constexpr Item kJogWithTarget{L::kCommand, numbers_of(Id::kJogWithTarget),
                                     "a manual move with a target not 0"};
// A manual (jog) or registration move changed while it runs: motion stops (J1.., R6..).
inline constexpr Item kJogConstantSpeed{L::kCommand, numbers_of(Id::kJogConstantSpeed),
                                        "a speed change on a constant-speed jog"};
inline constexpr Item kJogInvalidChange{L::kCommand, numbers_of(Id::kJogInvalidChange),
                                        "an invalid speed, accel or decel in a jog"};
inline constexpr Item kJogSpeedZero{L::kCommand, numbers_of(Id::kJogSpeedZero),
                                    "a jog's speed changed to 0"};
inline constexpr Item kJogTargetWritten{L::kCommand, numbers_of(Id::kJogTargetWritten),
                                        "a target written while a jog runs"};
inline constexpr Item kRegCountChanged{L::kCommand, numbers_of(Id::kRegCountChanged),
                                       "registration count changed after the start"};
inline constexpr Item kRegSpeedIncreased{L::kCommand, numbers_of(Id::kRegSpeedIncreased),
                                         "a registration move's speed increased"};
inline constexpr Item kRegRatesChanged{L::kCommand, numbers_of(Id::kRegRatesChanged),
                                       "registration accel or decel changed"};
inline constexpr Item kBlendNotStored{L::kCommand, numbers_of(Id::kBlendNotStored),
                                      "Run Blend with no profile stored"};
inline constexpr Item kBlendWhileBlending{L::kCommand, numbers_of(Id::kBlendWhileBlending),
                                          "blend programming while a blend runs"};
inline constexpr Item kHoldDuringBlend{L::kCommand, numbers_of(Id::kHoldDuringBlend),
                                       "Hold during a blend"};
inline constexpr Item kFollowerNoEncoder{L::kCommand, numbers_of(Id::kFollowerNoEncoder),
                                         "follower mode with no encoder configured"};
inline constexpr Item kFollowerWhileMoving{L::kCommand, numbers_of(Id::kFollowerWhileMoving),
                                           "follower mode while a motion runs"};
inline constexpr Item kFollowerRatio{L::kCommand, numbers_of(Id::kFollowerRatio),
                                     "follower ratio out of 1..32767"};
inline constexpr Item kFollowerSpeed{L::kCommand, numbers_of(Id::kFollowerSpeed),
                                     "follower with speed words not 0"};
inline constexpr Item kFollowerDirection{L::kCommand, numbers_of(Id::kFollowerDirection),
                                         "follower direction changed with no 0 scan"};
inline constexpr Item kFollowerOtherCommand{L::kCommand, numbers_of(Id::kFollowerOtherCommand),
                                            "a command other than +/- in follower mode"};
inline constexpr Item kFollowerReleased{L::kCommand, numbers_of(Id::kFollowerReleased),
                                        "follower flag cleared with a direction set"};
inline constexpr Item kFollowerSCurve{L::kCommand, numbers_of(Id::kFollowerSCurve),
                                      "S-curve with the follower"};
inline constexpr Item kFollowerLimit{L::kCommand, numbers_of(Id::kFollowerLimit),
                                     "follower mode with an end limit active"};
inline constexpr Item kPlannerFull{L::kCommand, numbers_of(Id::kPlannerFull),
                                   "the planner's queue is full (stepmod)"};

// ---- Invalid Profile ----
inline constexpr Item kProfileVpBelowVs{L::kInvalidProfile, numbers_of(Id::kProfileVpBelowVs),
                                        "programmed speed below starting speed"};
inline constexpr Item kProfileOutOfRange{L::kInvalidProfile, numbers_of(Id::kProfileOutOfRange),
                                         "a move parameter out of range"};
inline constexpr Item kProfileOverflow{L::kInvalidProfile, numbers_of(Id::kProfileOverflow),
                                       "the profile overflows 32-bit registers"};
inline constexpr Item kProfileReserved{L::kInvalidProfile, numbers_of(Id::kProfileReserved),
                                       "reserved words not 0"};
inline constexpr Item kBlendSegmentCount{L::kInvalidProfile, numbers_of(Id::kBlendSegmentCount),
                                         "blend segment count not 2..16"};
inline constexpr Item kBlendNoFinalDecel{L::kInvalidProfile, numbers_of(Id::kBlendNoFinalDecel),
                                         "blend profile without a final deceleration"};
inline constexpr Item kBlendBlockError{L::kInvalidProfile, numbers_of(Id::kBlendBlockError),
                                       "an error in a blend programming block"};
inline constexpr Item kBlendNotConfigured{L::kInvalidProfile, numbers_of(Id::kBlendNotConfigured),
                                          "blend message to an unconfigured channel"};
inline constexpr Item kBlendNoChannel{L::kInvalidProfile, numbers_of(Id::kBlendNoChannel),
                                      "blend message channel not 1 or 2"};

// ---- Input Error ----
inline constexpr Item kEStop{L::kInput, numbers_of(Id::kEStop), "the E-stop input activated"};
inline constexpr Item kLimitInMove{L::kInput, numbers_of(Id::kLimitInMove),
                                   "an end limit reached during a move"};
inline constexpr Item kStartTowardLimit{L::kInput, numbers_of(Id::kStartTowardLimit),
                                        "a start toward an active limit or E-stop"};
inline constexpr Item kHomingSecondLimit{L::kInput, numbers_of(Id::kHomingSecondLimit),
                                         "homing met the other limit after reversing"};
inline constexpr Item kHomingOppositeLimit{L::kInput, numbers_of(Id::kHomingOppositeLimit),
                                           "homing reached the opposite limit first"};

// ---- Home Invalid ----
inline constexpr Item kHomeFailed{L::kHomeInvalid, numbers_of(Id::kHomeFailed),
                                  "homing did not find home"};
inline constexpr Item kHomeLimitError{L::kHomeInvalid, numbers_of(Id::kHomeLimitError),
                                      "homing met the opposite or a second limit"};
inline constexpr Item kHomeTimeout{L::kHomeInvalid, numbers_of(Id::kHomeTimeout),
                                   "homing timeout expired"};

// ---- Position Invalid ----
inline constexpr Item kPiConfigured{L::kPositionInvalid, numbers_of(Id::kPiConfigured),
                                    "a configuration (the position is 0)"};
inline constexpr Item kPiImmediateStop{L::kPositionInvalid, numbers_of(Id::kPiImmediateStop),
                                       "Immediate Stop while moving"};
inline constexpr Item kPiEStop{L::kPositionInvalid, numbers_of(Id::kPiEStop),
                               "E-stop while moving"};
inline constexpr Item kPiLimit{L::kPositionInvalid, numbers_of(Id::kPiLimit),
                               "an end limit during a move"};
inline constexpr Item kPiPlcStopped{L::kPositionInvalid, numbers_of(Id::kPiPlcStopped),
                                    "the PLC left Run mode while moving"};
inline constexpr Item kPiLateEdge{L::kPositionInvalid, numbers_of(Id::kPiLateEdge),
                                  "a late-edge fault stopped it (stepmod)"};
inline constexpr Item kPiLeaseExpired{L::kPositionInvalid, numbers_of(Id::kPiLeaseExpired),
                                      "commissioning lease expired (stepmod)"};
inline constexpr Item kPiInputLost{L::kPositionInvalid, numbers_of(Id::kPiInputLost),
                                   "an input edge was lost (stepmod)"};
inline constexpr Item kPiFault{L::kPositionInvalid, numbers_of(Id::kPiFault),
                               "a fault stopped the axis"};

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
static_assert(kAll.size() == kItemCount, "one ItemId (item_ids.hpp) per Item, one Item per ItemId");

}  // namespace stepmod::module::axis::items

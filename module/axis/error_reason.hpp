#pragma once
// Why an error bit was set (the image's reason block, docs/error-reasons.md): the manual checklist
// item and one sentence. The shared axis code names a condition once (error_items.hpp); each
// module numbers its checklist items differently, so an Item carries every module's number.
#include <array>
#include <cstdint>
#include <string>

#include "core/module_shape.hpp"

namespace stepmod::module::axis {

// The checklist lists, one per error bit; the value is the list's digit in the item code.
enum class ErrorList : std::uint8_t {
  kConfiguration = 1,    // CFG
  kCommand = 2,          // CE
  kInvalidProfile = 3,   // IP
  kInput = 4,            // IE
  kHomeInvalid = 5,      // HI
  kPositionInvalid = 6,  // PI
};

// One condition that sets an error bit, with its item number in each module's list
// (0 = that module's list has no item for it: the reason names the list only). Numbers 91..99
// are stepmod's own items (conditions the manuals cannot have: a late edge, a lost lease), shown
// as S1..S9.
struct Item {
  ErrorList list;
  // The item's number in each module's list, in kModuleShapes' order (3601, 3602, 3202).
  std::array<std::uint8_t, kModuleShapes.size()> numbers;
  const char* what;  // the condition in general, for docs/error-reasons.md
  std::uint8_t number(ModuleType t) const noexcept {
    const std::size_t i = module_index(t);
    return i < numbers.size() ? numbers[i] : 0;
  }
};

// Item code = module digit (ModuleShape::reason_digit: 3601: 1, 3602: 2, 3202: 3) * 10000 +
// list digit * 100 + number.
// 0 means no reason. Stable: a code is never reused for another item.
std::uint32_t item_code(ModuleType t, ErrorList list, unsigned number) noexcept;
// "3601-CE-05", "3601-PI-S1", "3602-IP" (number 0).
std::string item_id(ModuleType t, ErrorList list, unsigned number);
// The same from a code; empty for 0 or a code that is not well-formed.
std::string item_id_of_code(std::uint32_t code);
const char* list_abbreviation(ErrorList list) noexcept;

inline constexpr std::size_t kReasonTextSize = 56;  // with its NUL (the image's char[56])

// The last reason recorded for an axis: the image's block of 64 bytes.
struct ErrorReason {
  std::uint32_t seq = 0;   // +1 per recorded reason
  std::uint32_t code = 0;  // item_code(), 0 = none yet
  std::array<char, kReasonTextSize> text{};
  bool operator==(const ErrorReason&) const = default;
};

}  // namespace stepmod::module::axis

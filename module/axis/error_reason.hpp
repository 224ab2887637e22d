#pragma once
// Why an error bit was set (the image's reason block, docs/error-reasons.md): the manual checklist
// item and one sentence. The shared axis code names a condition once (error_items.hpp); each
// module numbers its checklist items differently, so an Item carries every module's number.
#include <array>
#include <cstddef>
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
// (0 = that module's list has no item for it: the reason names the list only). Numbers 1..50 are
// the list's own numbers; from 51 on the tens digit is a letter and the units digit a number:
// the lettered items of the 3602's Command Error list (5x: B, blend; 6x: I, interpolated move;
// 7x: J, jog; 8x: R, registration) and stepmod's own items (9x: S; conditions the manuals
// cannot have, such as a late edge or a lost lease, or whose error the manuals leave open).
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
// "3601-CE-05", "3601-PI-S1", "3602-CE-I3", "3602-IP" (number 0).
std::string item_id(ModuleType t, ErrorList list, unsigned number);
// The same into `out` (at most `size` bytes with the NUL), for the control thread: no allocation.
void format_item_id(char* out, std::size_t size, ModuleType t, ErrorList list,
                    unsigned number) noexcept;
// The same from a code; empty for 0 or a code that is not well-formed.
std::string item_id_of_code(std::uint32_t code);
const char* list_abbreviation(ErrorList list) noexcept;
// The name of the list's error bit, as the manuals write it: "Configuration Error", ...
const char* list_bit_name(ErrorList list) noexcept;

inline constexpr std::size_t kReasonTextSize = 56;  // with its NUL (the image's char[56])

// The last reason recorded for an axis: the image's block of 64 bytes.
struct ErrorReason {
  std::uint32_t seq = 0;   // +1 per recorded reason
  std::uint32_t code = 0;  // item_code(), 0 = none yet
  std::array<char, kReasonTextSize> text{};
  bool operator==(const ErrorReason&) const = default;
};

}  // namespace stepmod::module::axis

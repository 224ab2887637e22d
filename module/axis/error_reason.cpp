#include "module/axis/error_reason.hpp"

#include <cstdio>

#include "core/enum_names.hpp"

namespace stepmod::module::axis {

namespace {
// In list order from kConfiguration = 1 (error_reason.hpp).
constexpr std::array<std::string_view, 6> kListAbbreviations = {"CFG", "CE", "IP",
                                                                "IE",  "HI", "PI"};
static_assert(static_cast<std::size_t>(ErrorList::kPositionInvalid) == kListAbbreviations.size());
constexpr std::array<std::string_view, 6> kListBitNames = {
    "Configuration Error", "Command Error", "Invalid Profile",
    "Input Error",         "Home Invalid",  "Position Invalid"};
static_assert(kListBitNames.size() == kListAbbreviations.size());
}  // namespace

const char* list_abbreviation(ErrorList list) noexcept {
  // The table's views are of literals, so data() is NUL-terminated.
  return enum_name(list, kListAbbreviations, 1).data();
}

const char* list_bit_name(ErrorList list) noexcept {
  return enum_name(list, kListBitNames, 1).data();  // of literals: NUL-terminated
}

std::uint32_t item_code(ModuleType t, ErrorList list, unsigned number) noexcept {
  return shape_of(t).reason_digit * 10000u + static_cast<unsigned>(list) * 100u + number;
}

void format_item_id(char* out, std::size_t size, ModuleType t, ErrorList list,
                    unsigned number) noexcept {
  const auto type = static_cast<unsigned>(t);
  const char* abbr = list_abbreviation(list);
  // The lettered items (error_reason.hpp): the tens digit from 5 on names the letter.
  static constexpr char kLetters[] = {'B', 'I', 'J', 'R', 'S'};
  if (number == 0) {
    std::snprintf(out, size, "%u-%s", type, abbr);
  } else if (number > 50 && number < 100 && number % 10 != 0) {
    std::snprintf(out, size, "%u-%s-%c%u", type, abbr, kLetters[number / 10 - 5], number % 10);
  } else {
    std::snprintf(out, size, "%u-%s-%02u", type, abbr, number);
  }
}

std::string item_id(ModuleType t, ErrorList list, unsigned number) {
  char id[24];
  format_item_id(id, sizeof id, t, list, number);
  return id;
}

std::string item_id_of_code(std::uint32_t code) {
  const unsigned m = code / 10000u;
  const unsigned l = code / 100u % 100u;
  const std::optional<ModuleType> t = module_type_from_reason_digit(m);
  if (!t || l < 1 || l > 6) return {};
  return item_id(*t, static_cast<ErrorList>(l), code % 100u);
}

}  // namespace stepmod::module::axis

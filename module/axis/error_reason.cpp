#include "module/axis/error_reason.hpp"

namespace stepmod::module::axis {

const char* list_abbreviation(ErrorList list) noexcept {
  switch (list) {
    case ErrorList::kConfiguration:
      return "CFG";
    case ErrorList::kCommand:
      return "CE";
    case ErrorList::kInvalidProfile:
      return "IP";
    case ErrorList::kInput:
      return "IE";
    case ErrorList::kHomeInvalid:
      return "HI";
    case ErrorList::kPositionInvalid:
      return "PI";
  }
  return "?";
}

std::uint32_t item_code(ModuleType t, ErrorList list, unsigned number) noexcept {
  return shape_of(t).reason_digit * 10000u + static_cast<unsigned>(list) * 100u + number;
}

std::string item_id(ModuleType t, ErrorList list, unsigned number) {
  std::string id = std::to_string(static_cast<unsigned>(t)) + "-" + list_abbreviation(list);
  if (number == 0) return id;
  if (number > 90) return id + "-S" + std::to_string(number - 90);
  return id + (number < 10 ? "-0" : "-") + std::to_string(number);
}

std::string item_id_of_code(std::uint32_t code) {
  const unsigned m = code / 10000u;
  const unsigned l = code / 100u % 100u;
  const std::optional<ModuleType> t = module_type_from_reason_digit(m);
  if (!t || l < 1 || l > 6) return {};
  return item_id(*t, static_cast<ErrorList>(l), code % 100u);
}

}  // namespace stepmod::module::axis

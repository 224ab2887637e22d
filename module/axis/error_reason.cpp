#include "module/axis/error_reason.hpp"

namespace stepmod::module::axis {

namespace {
unsigned module_digit(ModuleType t) noexcept {
  return t == ModuleType::k3601 ? 1u : t == ModuleType::k3602 ? 2u : 3u;
}
}  // namespace

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
  return module_digit(t) * 10000u + static_cast<unsigned>(list) * 100u + number;
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
  if (m < 1 || m > 3 || l < 1 || l > 6) return {};
  const ModuleType t = m == 1 ? ModuleType::k3601 : m == 2 ? ModuleType::k3602 : ModuleType::k3202;
  return item_id(t, static_cast<ErrorList>(l), code % 100u);
}

}  // namespace stepmod::module::axis

#include "gpio/chip_survey.hpp"

#include <algorithm>
#include <initializer_list>

namespace stepmod::gpio {

const GpioChipInfo* find_gpio_chip(const std::vector<GpioChipInfo>& chips,
                                   const std::string& chip) {
  if (chip.empty()) return nullptr;
  const bool number = chip.find_first_not_of("0123456789") == std::string::npos;
  const std::string name = number ? "gpiochip" + chip : chip;
  using Field = std::string GpioChipInfo::*;
  for (const Field match : {&GpioChipInfo::path, &GpioChipInfo::name, &GpioChipInfo::label}) {
    const auto it = std::find_if(chips.begin(), chips.end(),
                                 [&](const GpioChipInfo& c) { return c.*match == name; });
    if (it != chips.end()) return &*it;
  }
  return nullptr;
}

}  // namespace stepmod::gpio

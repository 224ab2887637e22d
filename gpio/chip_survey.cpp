#include "gpio/chip_survey.hpp"

#include <dirent.h>

#include <algorithm>
#include <initializer_list>

namespace stepmod::gpio {

std::vector<GpioChipInfo> list_gpio_chips(const std::string& dev_dir) {
  std::vector<GpioChipInfo> chips;
  DIR* d = opendir(dev_dir.c_str());
  if (d == nullptr) return chips;
  while (const dirent* e = readdir(d)) {
    const std::string name = e->d_name;
    if (name.rfind("gpiochip", 0) != 0) continue;
    if (auto chip = read_gpio_chip(dev_dir + "/" + name)) chips.push_back(std::move(*chip));
  }
  closedir(d);
  std::sort(chips.begin(), chips.end(),
            [](const GpioChipInfo& a, const GpioChipInfo& b) { return a.path < b.path; });
  return chips;
}

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

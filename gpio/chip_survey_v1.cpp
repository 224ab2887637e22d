// gpio/chip_survey.hpp on libgpiod 1.6.
#include <dirent.h>
#include <gpiod.h>

#include <algorithm>

#include "gpio/chip_survey.hpp"

namespace stepmod::gpio {

std::vector<GpioChipInfo> list_gpio_chips(const std::string& dev_dir) {
  std::vector<GpioChipInfo> chips;
  DIR* d = opendir(dev_dir.c_str());
  if (d == nullptr) return chips;
  while (const dirent* e = readdir(d)) {
    const std::string name = e->d_name;
    if (name.rfind("gpiochip", 0) != 0) continue;
    const std::string path = dev_dir + "/" + name;
    gpiod_chip* c = gpiod_chip_open(path.c_str());
    if (c == nullptr) continue;
    chips.push_back({path, gpiod_chip_name(c), gpiod_chip_label(c), gpiod_chip_num_lines(c)});
    gpiod_chip_close(c);
  }
  closedir(d);
  std::sort(chips.begin(), chips.end(),
            [](const GpioChipInfo& a, const GpioChipInfo& b) { return a.path < b.path; });
  return chips;
}

GpioLineUse gpio_line_use(const std::string& path, unsigned offset) {
  GpioLineUse use;
  gpiod_chip* c = gpiod_chip_open(path.c_str());
  if (c == nullptr) return use;
  if (offset < gpiod_chip_num_lines(c)) {
    if (gpiod_line* l = gpiod_chip_get_line(c, offset)) {
      use.exists = true;
      use.used = gpiod_line_is_used(l);
      const char* who = gpiod_line_consumer(l);
      use.consumer = who != nullptr ? who : "";
    }
  }
  gpiod_chip_close(c);
  return use;
}

}  // namespace stepmod::gpio

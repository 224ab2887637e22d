// gpio/chip_survey.hpp on libgpiod 2.
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
    const std::string path = dev_dir + "/" + name;
    if (name.rfind("gpiochip", 0) != 0 || !gpiod_is_gpiochip_device(path.c_str())) continue;
    gpiod_chip* c = gpiod_chip_open(path.c_str());
    if (c == nullptr) continue;
    if (gpiod_chip_info* info = gpiod_chip_get_info(c)) {
      chips.push_back({path, gpiod_chip_info_get_name(info), gpiod_chip_info_get_label(info),
                       static_cast<unsigned>(gpiod_chip_info_get_num_lines(info))});
      gpiod_chip_info_free(info);
    }
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
  if (gpiod_line_info* info = gpiod_chip_get_line_info(c, offset)) {
    use.exists = true;
    use.used = gpiod_line_info_is_used(info);
    const char* who = gpiod_line_info_get_consumer(info);
    use.consumer = who != nullptr ? who : "";
    gpiod_line_info_free(info);
  }
  gpiod_chip_close(c);
  return use;
}

}  // namespace stepmod::gpio

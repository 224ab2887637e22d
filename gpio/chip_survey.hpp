#pragma once
// What GPIO chips this machine has and whether a line is free, for `stepmodctl doctor`: the
// chips' names, labels (the Raspberry Pi 5's header is "pinctrl-rp1") and line counts, and a
// line's user. Built against the libgpiod generation the backend uses (chip_survey_v1.cpp for
// 1.6, chip_survey_v2.cpp for 2); the chip lookup (chip_survey.cpp) follows the backend's rules.
#include <optional>
#include <string>
#include <vector>

namespace stepmod::gpio {

struct GpioChipInfo {
  std::string path;   // "/dev/gpiochip0"
  std::string name;   // "gpiochip0"
  std::string label;  // "pinctrl-rp1"
  unsigned lines = 0;
};

struct GpioLineUse {
  bool exists = false;   // the chip has the offset
  bool used = false;     // requested by someone (or claimed by a kernel driver)
  std::string consumer;  // who, when the kernel says
};

// Every GPIO character device in `dev_dir` ("/dev"), by name; the ones that cannot be opened
// are left out.
std::vector<GpioChipInfo> list_gpio_chips(const std::string& dev_dir = "/dev");
// The chip a configuration's `chip` names, as the backend would open it: a path, a number
// ("0": gpiochip0), a name ("gpiochip4") or a label ("pinctrl-rp1"); nullptr if none.
const GpioChipInfo* find_gpio_chip(const std::vector<GpioChipInfo>& chips, const std::string& chip);
// One chip's name, label and line count; nullopt when `path` is no GPIO chip or cannot be
// opened (per libgpiod generation).
std::optional<GpioChipInfo> read_gpio_chip(const std::string& path);
// What the kernel says of a line (`consumer` may be null).
inline GpioLineUse line_use(bool used, const char* consumer) {
  return {true, used, consumer != nullptr ? consumer : ""};
}
// Whether `offset` of the chip at `path` is in use (nothing is requested).
GpioLineUse gpio_line_use(const std::string& path, unsigned offset);

}  // namespace stepmod::gpio

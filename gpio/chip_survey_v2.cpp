// gpio/chip_survey.hpp on libgpiod 2.
#include <gpiod.h>

#include "gpio/chip_survey.hpp"

namespace stepmod::gpio {

std::optional<GpioChipInfo> read_gpio_chip(const std::string& path) {
  if (!gpiod_is_gpiochip_device(path.c_str())) return std::nullopt;
  gpiod_chip* c = gpiod_chip_open(path.c_str());
  if (c == nullptr) return std::nullopt;
  std::optional<GpioChipInfo> out;
  if (gpiod_chip_info* info = gpiod_chip_get_info(c)) {
    out = GpioChipInfo{path, gpiod_chip_info_get_name(info), gpiod_chip_info_get_label(info),
                       static_cast<unsigned>(gpiod_chip_info_get_num_lines(info))};
    gpiod_chip_info_free(info);
  }
  gpiod_chip_close(c);
  return out;
}

GpioLineUse gpio_line_use(const std::string& path, unsigned offset) {
  gpiod_chip* c = gpiod_chip_open(path.c_str());
  if (c == nullptr) return {};
  gpiod_line_info* i = gpiod_chip_get_line_info(c, offset);  // null: no such offset
  const GpioLineUse use =
      i == nullptr ? GpioLineUse{}
                   : line_use(gpiod_line_info_is_used(i), gpiod_line_info_get_consumer(i));
  if (i != nullptr) gpiod_line_info_free(i);
  gpiod_chip_close(c);
  return use;
}

}  // namespace stepmod::gpio

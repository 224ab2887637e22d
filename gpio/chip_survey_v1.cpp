// gpio/chip_survey.hpp on libgpiod 1.6.
#include <gpiod.h>

#include "gpio/chip_survey.hpp"

namespace stepmod::gpio {

std::optional<GpioChipInfo> read_gpio_chip(const std::string& path) {
  gpiod_chip* c = gpiod_chip_open(path.c_str());
  if (c == nullptr) return std::nullopt;
  GpioChipInfo info{path, gpiod_chip_name(c), gpiod_chip_label(c), gpiod_chip_num_lines(c)};
  gpiod_chip_close(c);
  return info;
}

GpioLineUse gpio_line_use(const std::string& path, unsigned offset) {
  gpiod_chip* c = gpiod_chip_open(path.c_str());
  if (c == nullptr) return {};
  gpiod_line* l = offset < gpiod_chip_num_lines(c) ? gpiod_chip_get_line(c, offset) : nullptr;
  const GpioLineUse use = l == nullptr ? GpioLineUse{}
                                       : line_use(gpiod_line_is_used(l), gpiod_line_consumer(l));
  gpiod_chip_close(c);
  return use;
}

}  // namespace stepmod::gpio

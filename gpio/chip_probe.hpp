#pragma once
// Looking at the GPIO chips before anything is requested: which chips exist (what `gpiodetect`
// prints), which one a configuration's `chip` names (a path, a gpiochipN name or number, or the
// chip's label: "pinctrl-rp1" on a Raspberry Pi 5, whose gpiochip number differs between
// kernels), and whether every configured line is on it and free. `stepmodd --check` runs it, and
// the daemon at start-up, so that a wrong chip or line is refused with the chips that do exist.
// Read-only: chip and line info ioctls of the kernel's uAPI (<linux/gpio.h>), the same on
// libgpiod 1.6 and 2; no line is requested.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "gpio/axis_lines.hpp"

namespace stepmod::gpio {

struct ChipInfo {
  std::string path;   // /dev/gpiochip4
  std::string name;   // gpiochip4
  std::string label;  // pinctrl-rp1
  unsigned lines = 0;
  int open_errno = 0;  // not 0: the chip could not be opened (name and path only)
};

// Every /dev/gpiochipN under `dev`, by number.
std::vector<ChipInfo> list_chips(const std::string& dev = "/dev");

// The chip `wanted` names among `chips`, as libgpiod's lookup does: an absolute path, a number
// (N: gpiochipN), a name (gpiochipN) or a label. nullopt: no such chip.
std::optional<ChipInfo> find_chip(std::span<const ChipInfo> chips, const std::string& wanted);

// One line per chip, as gpiodetect prints them: "gpiochip4 [pinctrl-rp1] (54 lines)".
std::string chip_list_text(std::span<const ChipInfo> chips);

// What to do about a chip that is there but cannot be opened (EACCES: the gpio group).
std::string chip_access_hint(int err);

// The message for a chip that does not exist: the chips that do, and gpiodetect.
std::string chip_missing_message(const std::string& wanted, std::span<const ChipInfo> chips);

// A configured line and how the kernel sees it.
struct LineState {
  std::string key;  // axis1.step
  unsigned offset = 0;
  bool used = false;
  std::string consumer;
};

// Every configured line of `axes` with its config key, in configuration order.
std::vector<LineState> configured_lines(std::span<const AxisLines> axes);

// The problems of `lines` on `chip` (their `used`/`consumer` filled in): an offset past the
// chip's last line, a line another program (or a running stepmodd) holds. Empty: all fine.
std::vector<std::string> line_problems(const ChipInfo& chip, std::span<const LineState> lines);

// The whole check: the chip found (by list_chips/find_chip), opened, every configured line
// looked at. Throws std::runtime_error naming every problem; returns the chip.
ChipInfo probe_chip(const std::string& wanted, std::span<const AxisLines> axes,
                    const std::string& dev = "/dev");

}  // namespace stepmod::gpio

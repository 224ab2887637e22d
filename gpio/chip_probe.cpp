// The chip probe (gpio/chip_probe.hpp): chip and line info through the kernel's GPIO uAPI.
#include "gpio/chip_probe.hpp"

#include <fcntl.h>
#include <linux/gpio.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "gpio/gpiod_shared.hpp"

namespace stepmod::gpio {

namespace {

// An open chip, closed on every path.
struct ChipFd {
  int fd;
  explicit ChipFd(const std::string& path) : fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC)) {}
  ~ChipFd() {
    if (fd >= 0) ::close(fd);
  }
  ChipFd(const ChipFd&) = delete;
  ChipFd& operator=(const ChipFd&) = delete;
};

std::string c_text(const char* s, std::size_t n) {
  return std::string(s, strnlen(s, n));
}

ChipInfo read_chip(const std::string& path) {
  ChipInfo c;
  c.path = path;
  c.name = std::filesystem::path(path).filename().string();
  const ChipFd chip(path);
  gpiochip_info info{};
  if (chip.fd < 0 || ::ioctl(chip.fd, GPIO_GET_CHIPINFO_IOCTL, &info) != 0) {
    c.open_errno = errno != 0 ? errno : ENOENT;
    return c;
  }
  c.name = c_text(info.name, sizeof info.name);
  c.label = c_text(info.label, sizeof info.label);
  c.lines = info.lines;
  return c;
}

// gpiochip12 -> 12 (for the order); anything else after the numbered ones.
unsigned long chip_number(const std::string& name) {
  const std::string digits = name.substr(std::min<std::size_t>(name.size(), 8));
  if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) return ~0UL;
  return std::stoul(digits);
}

bool all_digits(const std::string& s) {
  return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
}

// Each configured line's kernel state (used, consumer) from the line info ioctl.
void read_line_states(const ChipInfo& chip, std::vector<LineState>& lines) {
  const ChipFd fd(chip.path);
  if (fd.fd < 0) return;
  for (LineState& l : lines) {
    if (l.offset >= chip.lines) continue;
    gpio_v2_line_info li{};
    li.offset = l.offset;
    if (::ioctl(fd.fd, GPIO_V2_GET_LINEINFO_IOCTL, &li) != 0) continue;
    l.used = (li.flags & GPIO_V2_LINE_FLAG_USED) != 0;
    l.consumer = c_text(li.consumer, sizeof li.consumer);
  }
}

}  // namespace

std::vector<ChipInfo> list_chips(const std::string& dev) {
  std::vector<ChipInfo> chips;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dev, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("gpiochip", 0) != 0 || !e.is_character_file(ec)) continue;
    chips.push_back(read_chip(e.path().string()));
  }
  std::sort(chips.begin(), chips.end(), [](const ChipInfo& a, const ChipInfo& b) {
    return chip_number(a.name) != chip_number(b.name) ? chip_number(a.name) < chip_number(b.name)
                                                      : a.name < b.name;
  });
  return chips;
}

std::optional<ChipInfo> find_chip(std::span<const ChipInfo> chips, const std::string& wanted) {
  if (wanted.empty()) return std::nullopt;
  const std::string name = all_digits(wanted) ? "gpiochip" + wanted : wanted;
  // Names and paths first: a label that happens to look like another chip's name loses.
  for (const ChipInfo& c : chips) {
    if (c.path == wanted || c.name == name) return c;
  }
  for (const ChipInfo& c : chips) {
    if (!c.label.empty() && c.label == wanted) return c;
  }
  return std::nullopt;
}

std::string chip_list_text(std::span<const ChipInfo> chips) {
  std::string out;
  for (const ChipInfo& c : chips) {
    out += "  " + c.name;
    if (c.open_errno != 0) {
      out += " (cannot open: " + std::string(std::strerror(c.open_errno)) + ")\n";
    } else {
      out += " [" + c.label + "] (" + std::to_string(c.lines) + " lines)\n";
    }
  }
  return out;
}

std::string chip_access_hint(int err) {
  if (err != EACCES && err != EPERM) return "";
  return " (the package's udev rule gives /dev/gpiochip* to the group 'gpio': "
         "`sudo usermod -aG gpio $USER`, then log in again; stepmodd@.service runs with it)";
}

std::string chip_missing_message(const std::string& wanted, std::span<const ChipInfo> chips) {
  std::string m = "GPIO chip '" + wanted + "' not found: ";
  if (chips.empty())
    return m + "this machine has no GPIO chip (no /dev/gpiochip*; `gpiodetect` lists none)";
  m += "[gpio] chip takes one of these names or labels (as `gpiodetect` lists them):\n";
  m += chip_list_text(chips);
  if (!m.empty() && m.back() == '\n') m.pop_back();
  return m;
}

std::vector<LineState> configured_lines(std::span<const AxisLines> axes) {
  std::vector<LineState> lines;
  for (unsigned a = 0; a < axes.size(); ++a) {
    for (unsigned l = 0; l < kOutputLinesPerAxis; ++l) {
      if (axes[a].out[l]) lines.push_back({line_key(a, false, l), *axes[a].out[l], false, ""});
    }
    if (axes[a].enable) {
      lines.push_back({line_key(a, false, kEnableKeyIndex), *axes[a].enable, false, ""});
    }
    if (axes[a].charge_pump) {
      lines.push_back(
          {line_key(a, false, kChargePumpKeyIndex), *axes[a].charge_pump, false, ""});
    }
    for (unsigned l = 0; l < kInputLinesPerAxis; ++l) {
      if (axes[a].in[l]) lines.push_back({line_key(a, true, l), *axes[a].in[l], false, ""});
    }
  }
  return lines;
}

std::vector<std::string> line_problems(const ChipInfo& chip, std::span<const LineState> lines) {
  std::vector<std::string> problems;
  const std::string where = "GPIO chip " + chip.name + " [" + chip.label + "]";
  for (const LineState& l : lines) {
    const std::string line = where + ", line " + std::to_string(l.offset) + " (" + l.key + ")";
    if (l.offset >= chip.lines) {
      problems.push_back(line + ": offset out of range (the chip has " +
                         std::to_string(chip.lines) + " lines, 0.." +
                         std::to_string(chip.lines == 0 ? 0 : chip.lines - 1) +
                         "; the right chip? `gpiodetect` lists them)");
    } else if (l.used) {
      const std::string who = l.consumer.empty() ? "?" : l.consumer;
      problems.push_back(line + ": line busy (used by '" + who + "'" +
                         (who == kGpiodConsumer ? ": a stepmodd running?" : "") + "; `gpioinfo " +
                         chip.name + "` shows it)");
    }
  }
  return problems;
}

ChipInfo probe_chip(const std::string& wanted, std::span<const AxisLines> axes,
                    const std::string& dev) {
  const std::vector<ChipInfo> chips = list_chips(dev);
  std::optional<ChipInfo> chip = find_chip(chips, wanted);
  if (!chip && !wanted.empty() && wanted.front() == '/' && std::filesystem::exists(wanted)) {
    chip = read_chip(wanted);  // a path outside `dev` (a symlink of the board's own)
  }
  if (!chip) throw std::runtime_error(chip_missing_message(wanted, chips));
  if (chip->open_errno != 0) {
    throw std::runtime_error("GPIO chip '" + wanted + "' (" + chip->path + "): cannot open: " +
                             std::strerror(chip->open_errno) + chip_access_hint(chip->open_errno));
  }
  std::vector<LineState> lines = configured_lines(axes);
  read_line_states(*chip, lines);
  const std::vector<std::string> problems = line_problems(*chip, lines);
  if (!problems.empty()) {
    std::string m;
    for (const std::string& p : problems) m += (m.empty() ? "" : "\n") + p;
    throw std::runtime_error(m);
  }
  return *chip;
}

}  // namespace stepmod::gpio

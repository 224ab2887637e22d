#pragma once
// The kernel's GPIO character device as the VM cases look at it from outside stepmodd: line info
// (who holds a line, its flags, its debounce) and holding a line as "another program". Through
// the v2 uAPI of <linux/gpio.h> directly (Linux >= 5.10), not libgpiod: these programs are built
// against libgpiod 1.6 (Debian 12) or 2 (Debian 13) like stepmodd, and must mean the same on both;
// what gpioinfo prints is this ioctl's answer.
#include <fcntl.h>
#include <linux/gpio.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <string>

#include "tests/vm/vm_harness.hpp"

namespace stepmod::vmtest {

inline std::string chip_path() {
  return "/dev/" + env("BOARD_CHIP");
}

struct KernelLine {
  bool used = false;
  std::string consumer;
  std::uint64_t flags = 0;        // GPIO_V2_LINE_FLAG_*
  std::uint32_t debounce_us = 0;  // GPIO_V2_LINE_ATTR_ID_DEBOUNCE, 0 if none
  bool has(std::uint64_t flag) const { return (flags & flag) != 0; }
};

// GPIO_V2_GET_LINEINFO_IOCTL on the board's chip.
inline KernelLine kernel_line(unsigned offset) {
  const int fd = ::open(chip_path().c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail("cannot open " + chip_path() + ": " + std::strerror(errno));
  gpio_v2_line_info li{};
  li.offset = offset;
  const int rc = ::ioctl(fd, GPIO_V2_GET_LINEINFO_IOCTL, &li);
  const int err = errno;
  ::close(fd);
  if (rc != 0) fail(fmt("line info of line %u: %s", offset, std::strerror(err)));
  KernelLine k;
  k.flags = li.flags;
  k.used = (li.flags & GPIO_V2_LINE_FLAG_USED) != 0;
  k.consumer.assign(li.consumer, strnlen(li.consumer, sizeof li.consumer));
  for (unsigned i = 0; i < li.num_attrs && i < GPIO_V2_LINE_NUM_ATTRS_MAX; ++i) {
    if (li.attrs[i].id == GPIO_V2_LINE_ATTR_ID_DEBOUNCE)
      k.debounce_us = li.attrs[i].debounce_period_us;
  }
  return k;
}

// Who holds a line ("" when free; "?" for a holder without a consumer name).
inline std::string line_user(unsigned offset) {
  const KernelLine k = kernel_line(offset);
  if (!k.used) return "";
  return k.consumer.empty() ? "?" : k.consumer;
}

// A line requested as an input by "another program" (consumer `consumer`) while it lives.
class HeldInput {
 public:
  HeldInput(unsigned offset, const char* consumer) {
    const int chip = ::open(chip_path().c_str(), O_RDONLY | O_CLOEXEC);
    if (chip < 0) fail("cannot open " + chip_path() + ": " + std::strerror(errno));
    gpio_v2_line_request req{};
    req.offsets[0] = offset;
    req.num_lines = 1;
    req.config.flags = GPIO_V2_LINE_FLAG_INPUT;
    std::strncpy(req.consumer, consumer, sizeof req.consumer - 1);
    const int rc = ::ioctl(chip, GPIO_V2_GET_LINE_IOCTL, &req);
    const int err = errno;
    ::close(chip);
    if (rc != 0) fail(fmt("cannot hold line %u: %s", offset, std::strerror(err)));
    fd_ = req.fd;
  }
  ~HeldInput() { ::close(fd_); }
  HeldInput(const HeldInput&) = delete;
  HeldInput& operator=(const HeldInput&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace stepmod::vmtest

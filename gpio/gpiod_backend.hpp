#pragma once
// Backend for `backend = "gpiod"`: a real GPIO chip through libgpiod 1.6 (the v1 character-device
// uAPI). Outputs are one bulk request written with one ioctl; input edges are read through
// io_uring (LineEventReader) with the kernel's timestamps.
#include <memory>
#include <span>
#include <string>

#include "gpio/axis_lines.hpp"
#include "gpio/backend.hpp"

namespace stepmod::gpio {

class GpiodBackend final : public Backend {
 public:
  // `chip`: name ("gpiochip0"), path ("/dev/gpiochip0"), label or number, as
  // gpiod_chip_open_lookup accepts. Requests every configured line (consumer "stepmod"); outputs
  // start low. Throws std::runtime_error naming the chip and the line (axis key and offset) when
  // the chip is missing, an offset is out of range or used twice, or a line is busy.
  GpiodBackend(const std::string& chip, std::span<const AxisLines> axes);
  ~GpiodBackend() override;
  GpiodBackend(const GpiodBackend&) = delete;
  GpiodBackend& operator=(const GpiodBackend&) = delete;

  unsigned axes() const noexcept override;
  void write(unsigned axis, OutputLine line, bool level, Nanos t) noexcept override;
  bool has_input(unsigned axis, InputLine line) const noexcept override;
  bool has_output(unsigned axis, OutputLine line) const noexcept override;
  bool read(unsigned axis, InputLine line) override;
  std::size_t wait_events(std::span<InputEvent> out, Nanos deadline) override;
  // Always 0: nothing is dropped between the kernel and the caller (see LineEventReader), and
  // the v1 uAPI has no sequence numbers, so an overflow of the kernel's own per-line FIFO (16
  // events) cannot be seen.
  std::uint64_t lost_events() const noexcept override;
  void idle_outputs() noexcept override;

  // Write errors seen by the pulse thread (it cannot report them itself).
  std::uint64_t write_errors() const noexcept;

 private:
  struct Impl;  // keeps libgpiod, liburing and <linux/gpio.h> out of the users' includes
  std::unique_ptr<Impl> d_;
};

}  // namespace stepmod::gpio

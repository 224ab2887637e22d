#pragma once
// Backend for `backend = "gpiod"`: a real GPIO chip through libgpiod. Two implementations of
// this one class, chosen by CMake from the libgpiod version pkg-config finds:
//   gpiod_backend_v1.cpp  libgpiod 1.6 (Debian 12), the v1 character-device uAPI
//   gpiod_backend_v2.cpp  libgpiod >= 2 (Debian 13), the v2 uAPI
// Every output write is one ioctl; input edges are read through io_uring (LineEventReader) with
// the kernel's CLOCK_MONOTONIC timestamps, and lost edges are counted (edge_record.hpp).
#include <memory>
#include <span>
#include <string>

#include "gpio/wired_backend.hpp"

namespace stepmod::gpio {

struct GpiodShared;

class GpiodBackend final : public WiredBackend {
 public:
  // `chip`: name ("gpiochip0"), path ("/dev/gpiochip0"), label or number (libgpiod 1.6's
  // gpiod_chip_open_lookup rules, on both versions). Requests every configured line (consumer
  // "stepmod") with its LineOptions; outputs start inactive. Throws std::runtime_error naming the
  // chip and the line (axis key and offset) when the chip is missing, an offset is out of range
  // or used twice, a line is busy, or an option cannot be applied (debounce on libgpiod 1.6).
  GpiodBackend(const std::string& chip, std::span<const AxisLines> axes);
  ~GpiodBackend() override;
  GpiodBackend(const GpiodBackend&) = delete;
  GpiodBackend& operator=(const GpiodBackend&) = delete;

  void write(unsigned axis, OutputLine line, bool level, Nanos t) noexcept override;
  bool read(unsigned axis, InputLine line) override;
  std::size_t wait_events(std::span<InputEvent> out, Nanos deadline) override;
  // Edges lost by the kernel (its per-line FIFO of 16 events overflowed): sequence-number gaps
  // with libgpiod 2; with 1.6 (no sequence numbers) only two same-direction edges in a row, so
  // an even number of lost edges is not seen. Nothing is dropped after the kernel.
  std::uint64_t lost_events() const noexcept override;
  void idle_outputs() noexcept override;
  void set_enable(unsigned axis, bool asserted) noexcept override;
  void set_charge_pump(unsigned axis, bool active) noexcept override;

  // Write errors seen by the pulse thread (it cannot report them itself).
  std::uint64_t write_errors() const noexcept;

 private:
  // The part both libgpiod generations share (gpio/gpiod_shared.hpp; the members that need no
  // libgpiod are defined once, over it), made by make_impl as the Impl of the generation whose
  // source CMake selected: keeps libgpiod, liburing and <linux/gpio.h> out of the users'
  // includes.
  std::unique_ptr<GpiodShared> d_;
  struct Impl;
  static std::unique_ptr<GpiodShared> make_impl(std::span<const AxisLines> lines);
  // The generation's Impl behind d_. A template, so that this one definition serves both
  // generations: it is instantiated only in the source that defines Impl (where I is complete).
  template <typename I = Impl>
  I& impl() noexcept {
    return static_cast<I&>(*d_);
  }
};

}  // namespace stepmod::gpio

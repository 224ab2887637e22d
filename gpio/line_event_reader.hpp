#pragma once
// Input edges of the v1 GPIO uAPI read through io_uring: one read of a batch of
// `struct gpioevent_data` kept in flight per line-event fd, so the control thread waits for all
// inputs and its scan deadline in one io_uring_wait_cqe_timeout. Separate from GpiodBackend so
// that it can be tested with plain pipes on machines without a GPIO chip.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "gpio/backend.hpp"

namespace stepmod::gpio {

class LineEventReader {
 public:
  struct Source {
    int fd = -1;  // a v1 line-event fd (or anything that yields gpioevent_data records)
    std::uint8_t axis = 0;
    InputLine line = InputLine::kCapture;
    std::string name;  // for error messages: "GPIO chip 'gpiochip0', line 5 (axis1.home)"
  };
  static constexpr unsigned kReadBatch = 16;  // records per read: the kernel's per-line FIFO size

  // Submits the first reads. Throws std::runtime_error if io_uring cannot be set up. The fds
  // stay owned by the caller and must stay open until the reader is destroyed.
  explicit LineEventReader(std::vector<Source> sources);
  ~LineEventReader();  // cancels the reads (before the caller closes the fds)
  LineEventReader(const LineEventReader&) = delete;
  LineEventReader& operator=(const LineEventReader&) = delete;

  // Blocks until at least one event is available or `deadline` (CLOCK_MONOTONIC) passes; returns
  // the number stored in `out`. Events of one source keep their order. Throws
  // std::runtime_error naming the source if a read fails.
  std::size_t wait(std::span<InputEvent> out, Nanos deadline);

  // Records whose size was not a whole gpioevent_data (never from the kernel).
  std::uint64_t malformed() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> d_;
};

}  // namespace stepmod::gpio

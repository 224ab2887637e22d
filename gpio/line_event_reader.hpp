#pragma once
// Input edges of the GPIO uAPI (v1 `struct gpioevent_data` or v2 `struct gpio_v2_line_event`
// records) read through io_uring: one read of a batch of records kept in flight per line-event
// fd, so the control thread waits for all inputs and its scan deadline in one
// io_uring_wait_cqe_timeout. Separate from GpiodBackend so that it can be tested with plain
// pipes on machines without a GPIO chip. Counts the edges its records show lost (edge_record.hpp).
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "gpio/backend.hpp"
#include "gpio/edge_record.hpp"

namespace stepmod::gpio {

class LineEventReader {
 public:
  struct Source {
    int fd = -1;  // a line-event fd (or anything that yields records of the reader's format)
    std::uint8_t axis = 0;
    InputLine line = InputLine::kCapture;
    std::string name;  // for error messages: "GPIO chip 'gpiochip0', line 5 (axis1.home)"
  };
  static constexpr unsigned kReadBatch = 16;  // records per read: the kernel's per-line FIFO size

  // Submits the first reads. Throws std::runtime_error if io_uring cannot be set up. The fds
  // stay owned by the caller and must stay open until the reader is destroyed.
  explicit LineEventReader(std::vector<Source> sources,
                           EdgeRecordFormat format = EdgeRecordFormat::kV1);
  ~LineEventReader();  // cancels the reads (before the caller closes the fds)
  LineEventReader(const LineEventReader&) = delete;
  LineEventReader& operator=(const LineEventReader&) = delete;

  // Blocks until at least one event is available or `deadline` (CLOCK_MONOTONIC) passes; returns
  // the number stored in `out`. Events of one source keep their order. Throws
  // std::runtime_error naming the source if a read fails.
  std::size_t wait(std::span<InputEvent> out, Nanos deadline);

  // Reads whose size was not a whole number of records (never from the kernel).
  std::uint64_t malformed() const noexcept;

  // Edges the records showed lost so far (sequence-number gaps on v2, repeated directions on
  // v1), all sources together. Control thread (the one calling wait()).
  std::uint64_t lost() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> d_;
};

}  // namespace stepmod::gpio

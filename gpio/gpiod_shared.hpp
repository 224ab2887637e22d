#pragma once
// What the two GpiodBackend implementations share (gpiod_backend_v1.cpp for libgpiod 1.6,
// gpiod_backend_v2.cpp for libgpiod 2; CMake builds one): the configured lines and what is said
// about them, the check that a configuration names each offset once and within the chip, the order
// in which a backend opens the chip and requests its lines, and the input event reader
// (gpiod_shared.cpp). Each backend's Impl derives from GpiodShared, adds its libgpiod handles
// and implements the steps. Internal to gpio/: no libgpiod in here.
#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "gpio/axis_lines.hpp"
#include "gpio/line_event_reader.hpp"

namespace stepmod::gpio {

inline constexpr const char* kGpiodConsumer = "stepmod";
// The line indexes that stand for the drive-enable and charge-pump outputs in line_key() and
// where().
inline constexpr unsigned kEnableKeyIndex = kOutputLinesPerAxis;
inline constexpr unsigned kChargePumpKeyIndex = kOutputLinesPerAxis + 1;

// The config key of a line: "axis1.step", "axis1.enable", "charge_pump.line" (the module's, on
// its first axis' lines).
std::string line_key(unsigned axis, bool input, unsigned line);

struct GpiodShared {
  explicit GpiodShared(std::span<const AxisLines> lines) : axes(lines) {}
  // The generation's Impl releases its lines (GpiodBackend::make_impl made it).
  virtual ~GpiodShared() = default;
  GpiodShared(const GpiodShared&) = delete;
  GpiodShared& operator=(const GpiodShared&) = delete;

  // GpiodBackend's constructor: opens `chip` and requests every configured line, axis by axis
  // in configuration order: each line claimed (checked) first, then requested. Throws
  // std::runtime_error naming the chip and the line; the Impl's destructor releases what was
  // requested.
  void setup(const std::string& chip);

  std::string chip_name;
  std::span<const AxisLines> axes;             // the backend's own (WiredBackend::lines())
  std::atomic<std::uint64_t> write_errors{0};  // by the pulse and control threads' writes
  std::unique_ptr<LineEventReader> events;     // null: no input wired
  // Per axis and InputLine: the index of the input in the backend's own list, -1 unwired.
  std::vector<std::array<int, kInputLinesPerAxis>> in_index;

  // "GPIO chip 'gpiochip0', line 5 (axis1.step)": how every message names a line.
  std::string where(unsigned axis, bool input, unsigned line, unsigned offset) const;
  // After a failed line request: `what`, "line busy" where errno says so, errno's text.
  static std::string request_error(const std::string& what);
  // The chip could not be opened (errno says why; ENOENT when it does not).
  [[noreturn]] static void throw_chip_not_found(const std::string& chip);

  // Each configured line once, in request order, before libgpiod is asked about it: within the
  // chip's lines, and our own use first (the lines are requested as they are claimed, so the
  // kernel would report a line this configuration names twice as busy "used by 'stepmod'").
  void claim(unsigned axis, bool input, unsigned line, unsigned offset);
  // After claim(): libgpiod could not read the line's info (errno says why), or another
  // consumer (`who`, null: unknown) holds it.
  [[noreturn]] void throw_no_line_info(unsigned axis, bool input, unsigned line,
                                       unsigned offset) const;
  [[noreturn]] void throw_line_busy(unsigned axis, bool input, unsigned line, unsigned offset,
                                    const char* who) const;

  // The index of a claimed input (read()), -1 when it is not wired.
  int input_index(unsigned axis, InputLine line) const noexcept {
    return axis < in_index.size() ? in_index[axis][static_cast<unsigned>(line)] : -1;
  }

  // The reader of the requested input lines' event fds (none: no reader).
  void start_events(std::vector<LineEventReader::Source> sources, EdgeRecordFormat format);

  // Pulse thread (write) and control thread (set_enable, set_charge_pump): one failed line
  // write, counted.
  void count_write_error() noexcept {
    write_errors.store(write_errors.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
  }

 private:
  // The steps of setup(), by the generation: open the chip (throw_chip_not_found when it
  // cannot) and return its number of lines; claim axis `a`'s lines (claim(), then libgpiod's
  // view of each); request every claimed line (start_events for the inputs).
  virtual std::size_t open(const std::string& chip) = 0;
  virtual void claim_axis(unsigned a) = 0;
  virtual void request_lines() = 0;

  std::vector<std::string> claimed_;  // offset -> "axis1.step"
};

}  // namespace stepmod::gpio

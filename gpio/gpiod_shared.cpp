// GpiodShared and the GpiodBackend members that only read the configured lines: one definition
// for both libgpiod generations (gpio/gpiod_shared.hpp).
#include "gpio/gpiod_shared.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "gpio/chip_probe.hpp"
#include "gpio/gpiod_backend.hpp"

namespace stepmod::gpio {

std::string line_key(unsigned axis, bool input, unsigned line) {
  const std::string_view k = input                     ? input_key(static_cast<InputLine>(line))
                             : line == kEnableKeyIndex ? std::string_view("enable")
                                                       : output_key(static_cast<OutputLine>(line));
  return "axis" + std::to_string(axis + 1) + "." + std::string(k);
}

std::string GpiodShared::where(unsigned axis, bool input, unsigned line, unsigned offset) const {
  return "GPIO chip '" + chip_name + "', line " + std::to_string(offset) + " (" +
         line_key(axis, input, line) + ")";
}

std::string GpiodShared::request_error(const std::string& what) {
  const int e = errno;
  return what + (e == EBUSY ? ": line busy" : "") + ": " + std::strerror(e);
}

void GpiodShared::throw_chip_not_found(const std::string& chip) {
  const int e = errno != 0 ? errno : ENOENT;
  if (e == ENOENT) throw std::runtime_error(chip_missing_message(chip, list_chips()));
  throw std::runtime_error("GPIO chip '" + chip + "' not accessible: " + std::strerror(e) +
                           chip_access_hint(e));
}

void GpiodShared::claim(unsigned axis, bool input, unsigned line, unsigned offset) {
  if (offset < claimed_.size() && !claimed_[offset].empty()) {
    throw std::runtime_error(where(axis, input, line, offset) + ": offset already used by " +
                             claimed_[offset]);
  }
  if (offset < claimed_.size()) claimed_[offset] = line_key(axis, input, line);
}

void GpiodShared::start_events(std::vector<LineEventReader::Source> sources,
                               EdgeRecordFormat format) {
  if (sources.empty()) return;
  try {
    events = std::make_unique<LineEventReader>(std::move(sources), format);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("GPIO chip '" + chip_name + "': input events: " + e.what());
  }
}

unsigned GpiodBackend::axes() const noexcept {
  return static_cast<unsigned>(shared().axes.size());
}

LineOptions GpiodBackend::line_options(unsigned axis, bool input, unsigned line) const noexcept {
  if (axis >= shared().axes.size()) return {};
  const AxisLines& a = shared().axes[axis];
  if (input) return line < kInputLinesPerAxis ? a.in_opt[line] : LineOptions{};
  return line < kOutputLinesPerAxis ? a.out_opt[line] : LineOptions{};
}

bool GpiodBackend::has_input(unsigned axis, InputLine line) const noexcept {
  return axis < shared().axes.size() && shared().axes[axis].has_input(line);
}

bool GpiodBackend::has_output(unsigned axis, OutputLine line) const noexcept {
  return axis < shared().axes.size() && shared().axes[axis].has_output(line);
}

std::size_t GpiodBackend::wait_events(std::span<InputEvent> out, Nanos deadline) {
  if (!shared().events) {  // no input wired: nothing can arrive
    sleep_until(deadline);
    return 0;
  }
  return shared().events->wait(out, deadline);
}

std::uint64_t GpiodBackend::lost_events() const noexcept {
  return shared().events ? shared().events->lost() : 0;
}

std::uint64_t GpiodBackend::write_errors() const noexcept {
  return shared().write_errors.load(std::memory_order_relaxed);
}

}  // namespace stepmod::gpio

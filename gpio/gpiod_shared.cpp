// GpiodShared and the GpiodBackend members that need no libgpiod: one definition for both
// libgpiod generations (gpio/gpiod_shared.hpp).
#include "gpio/gpiod_shared.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "gpio/chip_probe.hpp"
#include "gpio/gpiod_backend.hpp"
#include "gpio/line_options.hpp"

namespace stepmod::gpio {

// The generation CMake selected (STEPMOD_LIBGPIOD_MAJOR, gpio/CMakeLists.txt): only libgpiod 2's
// v2 uAPI has per-line debounce.
GpiodCapabilities gpiod_capabilities() noexcept {
  return {STEPMOD_LIBGPIOD_MAJOR, STEPMOD_LIBGPIOD_MAJOR >= 2};
}

std::string line_key(unsigned axis, bool input, unsigned line) {
  if (!input && line == kChargePumpKeyIndex) return "charge_pump.line";
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

void GpiodShared::setup(const std::string& chip) {
  chip_name = chip;
  claimed_.assign(open(chip), {});
  in_index.assign(axes.size(), {});
  for (auto& index : in_index) index.fill(-1);
  for (unsigned a = 0; a < axes.size(); ++a) claim_axis(a);
  request_lines();
}

void GpiodShared::claim(unsigned axis, bool input, unsigned line, unsigned offset) {
  const std::size_t n = claimed_.size();  // the chip's lines
  if (offset >= n) {
    throw std::runtime_error(where(axis, input, line, offset) +
                             ": offset out of range (the chip has " + std::to_string(n) +
                             " lines, 0.." + std::to_string(n - 1) + ")");
  }
  if (!claimed_[offset].empty()) {
    throw std::runtime_error(where(axis, input, line, offset) + ": offset already used by " +
                             claimed_[offset]);
  }
  claimed_[offset] = line_key(axis, input, line);
}

void GpiodShared::throw_no_line_info(unsigned axis, bool input, unsigned line,
                                     unsigned offset) const {
  throw std::runtime_error(where(axis, input, line, offset) +
                           ": cannot get line info: " + std::strerror(errno));
}

void GpiodShared::throw_line_busy(unsigned axis, bool input, unsigned line, unsigned offset,
                                  const char* who) const {
  throw std::runtime_error(where(axis, input, line, offset) + ": line busy (used by '" +
                           (who != nullptr ? who : "?") + "')");
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

GpiodBackend::GpiodBackend(const std::string& chip, std::span<const AxisLines> axes)
    : WiredBackend({axes.begin(), axes.end()}), d_(make_impl(lines())) {
  d_->setup(chip);
}

GpiodBackend::~GpiodBackend() = default;

std::size_t GpiodBackend::wait_events(std::span<InputEvent> out, Nanos deadline) {
  if (!d_->events) {  // no input wired: nothing can arrive
    sleep_until(deadline);
    return 0;
  }
  return d_->events->wait(out, deadline);
}

std::uint64_t GpiodBackend::lost_events() const noexcept {
  return d_->events ? d_->events->lost() : 0;
}

std::uint64_t GpiodBackend::write_errors() const noexcept {
  return d_->write_errors.load(std::memory_order_relaxed);
}

}  // namespace stepmod::gpio

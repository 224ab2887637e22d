#include "gpio/gpiod_backend.hpp"

#include <gpiod.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "gpio/line_event_reader.hpp"

namespace stepmod::gpio {

namespace {
constexpr const char* kConsumer = "stepmod";
constexpr unsigned kEnableKeyIndex = kOutputLinesPerAxis;  // where(): the enable line

// libgpiod 1.6 request flags of a line's options (bias flags: since libgpiod 1.5 / Linux 5.5).
int request_flags(const LineOptions& o) {
  int flags = o.active_low ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0;
  if (o.drive == Drive::kOpenDrain) flags |= GPIOD_LINE_REQUEST_FLAG_OPEN_DRAIN;
  if (o.drive == Drive::kOpenSource) flags |= GPIOD_LINE_REQUEST_FLAG_OPEN_SOURCE;
  if (o.bias == Bias::kPullUp) flags |= GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP;
  if (o.bias == Bias::kPullDown) flags |= GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_DOWN;
  if (o.bias == Bias::kDisabled) flags |= GPIOD_LINE_REQUEST_FLAG_BIAS_DISABLE;
  return flags;
}
}  // namespace

GpiodCapabilities gpiod_capabilities() noexcept {
  return {1, false};
}

struct GpiodBackend::Impl {
  struct Input {
    gpiod_line* line = nullptr;
    int fd = -1;
    std::uint8_t axis = 0;
    InputLine which = InputLine::kCapture;
    unsigned offset = 0;
  };

  std::string chip_name;
  gpiod_chip* chip = nullptr;
  std::vector<AxisLines> axes;

  // Outputs: one request per line (each with its own flags: drive, active-low), so one write is
  // one ioctl (GPIOHANDLE_SET_LINE_VALUES_IOCTL) on that line's handle.
  std::vector<std::array<gpiod_line*, kOutputLinesPerAxis>> out_lines;  // null: unwired
  std::vector<gpiod_line*> outputs_requested;
  std::vector<gpiod_line*> enable_lines;  // per axis, null: none
  std::atomic<std::uint64_t> write_errors{0};

  // Inputs: one event request per line; their fds are read by `events`.
  std::vector<std::array<int, kInputLinesPerAxis>> in_index;  // index into `inputs`, -1 unwired
  std::vector<Input> inputs;
  std::unique_ptr<LineEventReader> events;

  // "axis1.step", "axis1.enable": the config key of a line.
  static std::string key(unsigned axis, bool input, unsigned line) {
    const std::string_view k = input ? input_key(static_cast<InputLine>(line))
                               : line == kEnableKeyIndex
                                   ? std::string_view("enable")
                                   : output_key(static_cast<OutputLine>(line));
    return "axis" + std::to_string(axis + 1) + "." + std::string(k);
  }

  std::string where(unsigned axis, bool input, unsigned line, unsigned offset) const {
    return "GPIO chip '" + chip_name + "', line " + std::to_string(offset) + " (" +
           key(axis, input, line) + ")";
  }

  gpiod_line* get_line(unsigned axis, bool input, unsigned line, unsigned offset) {
    const unsigned n = gpiod_chip_num_lines(chip);
    if (offset >= n) {
      throw std::runtime_error(where(axis, input, line, offset) +
                               ": offset out of range (the chip has " + std::to_string(n) +
                               " lines, 0.." + std::to_string(n - 1) + ")");
    }
    gpiod_line* l = gpiod_chip_get_line(chip, offset);
    if (l == nullptr) {
      throw std::runtime_error(where(axis, input, line, offset) +
                               ": cannot get line info: " + std::strerror(errno));
    }
    // Checked before requesting so that the message names the line and its present user (a
    // failed bulk request only says EBUSY for the whole set).
    if (gpiod_line_is_used(l)) {
      const char* who = gpiod_line_consumer(l);
      throw std::runtime_error(where(axis, input, line, offset) + ": line busy (used by '" +
                               (who != nullptr ? who : "?") + "')");
    }
    return l;
  }

  std::string request_error(const std::string& what) const {
    const int e = errno;
    return what + (e == EBUSY ? ": line busy" : "") + ": " + std::strerror(e);
  }

  void release() noexcept {
    // The reader first: it cancels the reads that use the event fds.
    events.reset();
    for (gpiod_line* l : outputs_requested) {
      gpiod_line_set_value(l, 0);
      gpiod_line_release(l);
    }
    outputs_requested.clear();
    for (Input& in : inputs) {
      if (in.fd >= 0) gpiod_line_release(in.line);
      in.fd = -1;
    }
    if (chip != nullptr) gpiod_chip_close(chip);
    chip = nullptr;
  }
};

GpiodBackend::GpiodBackend(const std::string& chip, std::span<const AxisLines> axes)
    : d_(std::make_unique<Impl>()) {
  Impl& d = *d_;
  d.chip_name = chip;
  d.axes.assign(axes.begin(), axes.end());
  d.chip = gpiod_chip_open_lookup(chip.c_str());
  if (d.chip == nullptr) {
    const int e = errno;
    throw std::runtime_error("GPIO chip '" + chip + "' not found or not accessible: " +
                             std::strerror(e != 0 ? e : ENOENT));
  }
  try {
    std::vector<std::string> used(gpiod_chip_num_lines(d.chip));  // offset -> "axis1.step"
    const auto claim = [&](unsigned a, bool input, unsigned line, unsigned offset) {
      // Our own use first: the lines are requested as they are claimed, so the kernel would
      // report a line this configuration names twice as busy "used by 'stepmod'".
      if (offset < used.size() && !used[offset].empty()) {
        throw std::runtime_error(d.where(a, input, line, offset) + ": offset already used by " +
                                 used[offset]);
      }
      gpiod_line* l = d.get_line(a, input, line, offset);
      used[offset] = Impl::key(a, input, line);
      return l;
    };

    d.out_lines.assign(axes.size(), {nullptr, nullptr, nullptr});
    d.in_index.resize(axes.size());
    for (unsigned a = 0; a < axes.size(); ++a) {
      d.in_index[a].fill(-1);
      for (unsigned l = 0; l < kOutputLinesPerAxis; ++l) {
        if (!axes[a].out[l]) continue;
        gpiod_line* line = claim(a, false, l, *axes[a].out[l]);
        const gpiod_line_request_config rc{kConsumer, GPIOD_LINE_REQUEST_DIRECTION_OUTPUT,
                                           request_flags(axes[a].out_opt[l])};
        if (gpiod_line_request(line, &rc, 0) != 0) {
          throw std::runtime_error(
              d.request_error(d.where(a, false, l, *axes[a].out[l]) + ": requesting the output"));
        }
        d.outputs_requested.push_back(line);
        d.out_lines[a][l] = line;
      }
      d.enable_lines.push_back(nullptr);
      if (axes[a].enable) {
        gpiod_line* line = claim(a, false, kEnableKeyIndex, *axes[a].enable);
        const gpiod_line_request_config rc{kConsumer, GPIOD_LINE_REQUEST_DIRECTION_OUTPUT,
                                           request_flags(axes[a].enable_opt)};
        if (gpiod_line_request(line, &rc, 0) != 0) {
          throw std::runtime_error(d.request_error(
              d.where(a, false, kEnableKeyIndex, *axes[a].enable) + ": requesting the output"));
        }
        d.outputs_requested.push_back(line);
        d.enable_lines.back() = line;
      }
      for (unsigned l = 0; l < kInputLinesPerAxis; ++l) {
        if (!axes[a].in[l]) continue;
        Impl::Input in;
        in.line = claim(a, true, l, *axes[a].in[l]);
        in.axis = static_cast<std::uint8_t>(a);
        in.which = static_cast<InputLine>(l);
        in.offset = *axes[a].in[l];
        d.in_index[a][l] = static_cast<int>(d.inputs.size());
        d.inputs.push_back(in);
      }
    }

    for (Impl::Input& in : d.inputs) {
      const LineOptions& o = axes[in.axis].in_opt[static_cast<unsigned>(in.which)];
      if (o.debounce_us != 0) {
        throw std::runtime_error(
            d.where(in.axis, true, static_cast<unsigned>(in.which), in.offset) +
            ": debounce_us needs libgpiod 2 (this stepmod is built with "
            "libgpiod 1.6, whose v1 uAPI has no debounce)");
      }
      if (gpiod_line_request_both_edges_events_flags(in.line, kConsumer, request_flags(o)) != 0) {
        throw std::runtime_error(
            d.request_error(d.where(in.axis, true, static_cast<unsigned>(in.which), in.offset) +
                            ": requesting edge events"));
      }
      in.fd = gpiod_line_event_get_fd(in.line);
    }

    if (!d.inputs.empty()) {
      std::vector<LineEventReader::Source> sources;
      for (const Impl::Input& in : d.inputs) {
        sources.push_back({in.fd, in.axis, in.which,
                           d.where(in.axis, true, static_cast<unsigned>(in.which), in.offset)});
      }
      try {
        d.events = std::make_unique<LineEventReader>(std::move(sources));
      } catch (const std::runtime_error& e) {
        throw std::runtime_error("GPIO chip '" + chip + "': input events: " + e.what());
      }
    }
  } catch (...) {
    d.release();
    throw;
  }
}

GpiodBackend::~GpiodBackend() {
  d_->release();
}

unsigned GpiodBackend::axes() const noexcept {
  return static_cast<unsigned>(d_->axes.size());
}

void GpiodBackend::write(unsigned axis, OutputLine line, bool level, Nanos /*t*/) noexcept {
  Impl& d = *d_;
  gpiod_line* l = d.out_lines[axis][static_cast<unsigned>(line)];
  if (l == nullptr) return;
  // One ioctl on the line's handle (libgpiod builds its one-line bulk on the stack).
  if (gpiod_line_set_value(l, level ? 1 : 0) != 0) {
    d.write_errors.store(d.write_errors.load(std::memory_order_relaxed) + 1,
                         std::memory_order_relaxed);
  }
}

LineOptions GpiodBackend::line_options(unsigned axis, bool input, unsigned line) const noexcept {
  if (axis >= d_->axes.size()) return {};
  const AxisLines& a = d_->axes[axis];
  if (input) return line < kInputLinesPerAxis ? a.in_opt[line] : LineOptions{};
  return line < kOutputLinesPerAxis ? a.out_opt[line] : LineOptions{};
}

bool GpiodBackend::has_input(unsigned axis, InputLine line) const noexcept {
  return axis < d_->axes.size() && d_->axes[axis].has_input(line);
}

bool GpiodBackend::has_output(unsigned axis, OutputLine line) const noexcept {
  return axis < d_->axes.size() && d_->axes[axis].has_output(line);
}

bool GpiodBackend::read(unsigned axis, InputLine line) {
  Impl& d = *d_;
  if (axis >= d.in_index.size()) return false;
  const int i = d.in_index[axis][static_cast<unsigned>(line)];
  if (i < 0) return false;
  const Impl::Input& in = d.inputs[static_cast<std::size_t>(i)];
  const int v = gpiod_line_get_value(in.line);
  if (v < 0) {
    throw std::runtime_error(d.where(axis, true, static_cast<unsigned>(line), in.offset) +
                             ": reading the level: " + std::strerror(errno));
  }
  return v != 0;
}

std::size_t GpiodBackend::wait_events(std::span<InputEvent> out, Nanos deadline) {
  Impl& d = *d_;
  if (!d.events) {  // no input wired: nothing can arrive
    sleep_until(deadline);
    return 0;
  }
  return d.events->wait(out, deadline);
}

std::uint64_t GpiodBackend::lost_events() const noexcept {
  return d_->events ? d_->events->lost() : 0;
}

std::uint64_t GpiodBackend::write_errors() const noexcept {
  return d_->write_errors.load(std::memory_order_relaxed);
}

void GpiodBackend::set_enable(unsigned axis, bool asserted) noexcept {
  if (axis >= d_->enable_lines.size() || d_->enable_lines[axis] == nullptr) return;
  if (gpiod_line_set_value(d_->enable_lines[axis], asserted ? 1 : 0) != 0) {
    d_->write_errors.fetch_add(1, std::memory_order_relaxed);
  }
}

void GpiodBackend::idle_outputs() noexcept {
  Impl& d = *d_;
  for (gpiod_line* l : d.outputs_requested) gpiod_line_set_value(l, 0);
}

}  // namespace stepmod::gpio

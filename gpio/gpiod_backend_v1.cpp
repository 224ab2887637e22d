#include "gpio/gpiod_backend.hpp"

#include <gpiod.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "gpio/gpiod_shared.hpp"

namespace stepmod::gpio {

namespace {

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

struct GpiodBackend::Impl final : GpiodShared {
  explicit Impl(std::span<const AxisLines> lines)
      : GpiodShared(lines), out_lines(lines.size(), {nullptr, nullptr, nullptr}) {}
  ~Impl() override { release(); }  // not copyable: GpiodShared is not

  struct Input {
    gpiod_line* line = nullptr;
    int fd = -1;
    std::uint8_t axis = 0;
    InputLine which = InputLine::kCapture;
    unsigned offset = 0;
  };

  gpiod_chip* chip = nullptr;

  // Outputs: one request per line (each with its own flags: drive, active-low), so one write is
  // one ioctl (GPIOHANDLE_SET_LINE_VALUES_IOCTL) on that line's handle.
  std::vector<std::array<gpiod_line*, kOutputLinesPerAxis>> out_lines;  // null: unwired
  std::vector<gpiod_line*> outputs_requested;
  std::vector<gpiod_line*> enable_lines;  // per axis, null: none
  std::vector<gpiod_line*> pump_lines;    // per axis (the first's at most), null: none

  // Inputs: one event request per line; their fds are read by `events`.
  std::vector<Input> inputs;

  std::size_t open(const std::string& name) override;
  gpiod_line* claim_line(unsigned axis, bool input, unsigned line, unsigned offset);
  gpiod_line* request_output(unsigned axis, unsigned line, unsigned offset, const LineOptions& o);
  void claim_axis(unsigned a) override;
  void request_lines() override;
  std::string input_name(const Input& in) const {
    return where(in.axis, true, static_cast<unsigned>(in.which), in.offset);
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

std::size_t GpiodBackend::Impl::open(const std::string& name) {
  chip = gpiod_chip_open_lookup(name.c_str());
  if (chip == nullptr) throw_chip_not_found(name);
  return gpiod_chip_num_lines(chip);
}

// One configured line, claimed (once) and checked before requesting so that the message names
// the line and its present user (a failed bulk request only says EBUSY for the whole set).
gpiod_line* GpiodBackend::Impl::claim_line(unsigned axis, bool input, unsigned line,
                                           unsigned offset) {
  claim(axis, input, line, offset);
  gpiod_line* l = gpiod_chip_get_line(chip, offset);
  if (l == nullptr) throw_no_line_info(axis, input, line, offset);
  if (gpiod_line_is_used(l)) throw_line_busy(axis, input, line, offset, gpiod_line_consumer(l));
  return l;
}

gpiod_line* GpiodBackend::Impl::request_output(unsigned axis, unsigned line, unsigned offset,
                                               const LineOptions& o) {
  gpiod_line* l = claim_line(axis, false, line, offset);
  const gpiod_line_request_config rc{kGpiodConsumer, GPIOD_LINE_REQUEST_DIRECTION_OUTPUT,
                                     request_flags(o)};
  if (gpiod_line_request(l, &rc, 0) != 0) {
    throw std::runtime_error(
        request_error(where(axis, false, line, offset) + ": requesting the output"));
  }
  outputs_requested.push_back(l);
  return l;
}

// One axis' lines in configuration order: outputs requested at once, inputs claimed (requested
// by request_lines()).
void GpiodBackend::Impl::claim_axis(unsigned a) {
  const AxisLines& lines = axes[a];
  for (unsigned l = 0; l < kOutputLinesPerAxis; ++l) {
    if (lines.out[l]) out_lines[a][l] = request_output(a, l, *lines.out[l], lines.out_opt[l]);
  }
  enable_lines.push_back(nullptr);
  if (lines.enable) {
    enable_lines.back() = request_output(a, kEnableKeyIndex, *lines.enable, lines.enable_opt);
  }
  pump_lines.push_back(nullptr);
  if (lines.charge_pump) {
    pump_lines.back() =
        request_output(a, kChargePumpKeyIndex, *lines.charge_pump, lines.charge_pump_opt);
  }
  for (unsigned l = 0; l < kInputLinesPerAxis; ++l) {
    if (!lines.in[l]) continue;
    Input in;
    in.line = claim_line(a, true, l, *lines.in[l]);
    in.axis = static_cast<std::uint8_t>(a);
    in.which = static_cast<InputLine>(l);
    in.offset = *lines.in[l];
    in_index[a][l] = static_cast<int>(inputs.size());
    inputs.push_back(in);
  }
}

// Edge events on every claimed input, and the reader of their fds (the outputs were requested as
// they were claimed).
void GpiodBackend::Impl::request_lines() {
  for (Input& in : inputs) {
    const LineOptions& o = axes[in.axis].in_opt[static_cast<unsigned>(in.which)];
    if (o.debounce_us != 0) {
      throw std::runtime_error(input_name(in) +
                               ": debounce_us needs libgpiod 2 (this stepmod is built with "
                               "libgpiod 1.6, whose v1 uAPI has no debounce)");
    }
    if (gpiod_line_request_both_edges_events_flags(in.line, kGpiodConsumer, request_flags(o)) !=
        0) {
      throw std::runtime_error(request_error(input_name(in) + ": requesting edge events"));
    }
    in.fd = gpiod_line_event_get_fd(in.line);
  }
  std::vector<LineEventReader::Source> sources;
  for (const Input& in : inputs) sources.push_back({in.fd, in.axis, in.which, input_name(in)});
  start_events(std::move(sources), EdgeRecordFormat::kV1);
}

std::unique_ptr<GpiodShared> GpiodBackend::make_impl(std::span<const AxisLines> lines) {
  return std::make_unique<Impl>(lines);
}

void GpiodBackend::write(unsigned axis, OutputLine line, bool level, Nanos /*t*/) noexcept {
  Impl& d = impl();
  gpiod_line* l = d.out_lines[axis][static_cast<unsigned>(line)];
  if (l == nullptr) return;
  // One ioctl on the line's handle (libgpiod builds its one-line bulk on the stack).
  if (gpiod_line_set_value(l, level ? 1 : 0) != 0) d.count_write_error();
}

bool GpiodBackend::read(unsigned axis, InputLine line) {
  Impl& d = impl();
  const int i = d.input_index(axis, line);
  if (i < 0) return false;
  const Impl::Input& in = d.inputs[static_cast<std::size_t>(i)];
  const int v = gpiod_line_get_value(in.line);
  if (v < 0)
    throw std::runtime_error(d.input_name(in) + ": reading the level: " + std::strerror(errno));
  return v != 0;
}

namespace {
// A control-thread output (drive enable, charge pump) of `lines`, by axis; null: none.
void set_control_line(GpiodShared& d, const std::vector<gpiod_line*>& lines, unsigned axis,
                      bool active) noexcept {
  if (axis >= lines.size() || lines[axis] == nullptr) return;
  if (gpiod_line_set_value(lines[axis], active ? 1 : 0) != 0) {
    d.write_errors.fetch_add(1, std::memory_order_relaxed);
  }
}
}  // namespace

void GpiodBackend::set_enable(unsigned axis, bool asserted) noexcept {
  set_control_line(impl(), impl().enable_lines, axis, asserted);
}

void GpiodBackend::set_charge_pump(unsigned axis, bool active) noexcept {
  set_control_line(impl(), impl().pump_lines, axis, active);
}

void GpiodBackend::idle_outputs() noexcept {
  Impl& d = impl();
  for (gpiod_line* l : d.outputs_requested) gpiod_line_set_value(l, 0);
}

}  // namespace stepmod::gpio

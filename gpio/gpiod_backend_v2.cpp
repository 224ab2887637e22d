// GpiodBackend for libgpiod >= 2 (the v2 character-device uAPI). CMake builds this file instead
// of gpiod_backend_v1.cpp when pkg-config finds libgpiod 2.
//
// Outputs: one request for all output lines (per-line settings: drive, active-low); a write is
// gpiod_line_request_set_value, one GPIO_V2_LINE_SET_VALUES_IOCTL with a one-line mask, built on
// the stack (no allocation: fit for the pulse thread).
// Inputs: one request per line (each line its own kernel FIFO, so a busy encoder line cannot push
// a limit switch's edge out of a shared one), both edges, CLOCK_MONOTONIC timestamps. The
// request fds are read by LineEventReader as raw `struct gpio_v2_line_event` records through
// io_uring, not through gpiod_edge_event_buffer: libgpiod's reader is a blocking read() into its
// own buffer per request, which would need a poll or an io_uring poll per fd and a second
// syscall per batch; the record layout is kernel ABI (linux/gpio.h), the same one libgpiod reads.
#include <gpiod.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "gpio/gpiod_backend.hpp"
#include "gpio/gpiod_shared.hpp"

namespace stepmod::gpio {

namespace {

// libgpiod 2's value of each line option, in its enum's order (gpio/line_options.hpp).
constexpr std::array kBiasOf{GPIOD_LINE_BIAS_AS_IS, GPIOD_LINE_BIAS_PULL_UP,
                             GPIOD_LINE_BIAS_PULL_DOWN, GPIOD_LINE_BIAS_DISABLED};
static_assert(kBiasOf.size() == static_cast<std::size_t>(Bias::kDisabled) + 1);
constexpr std::array kDriveOf{GPIOD_LINE_DRIVE_PUSH_PULL, GPIOD_LINE_DRIVE_OPEN_DRAIN,
                              GPIOD_LINE_DRIVE_OPEN_SOURCE};
static_assert(kDriveOf.size() == static_cast<std::size_t>(Drive::kOpenSource) + 1);

// Owners of libgpiod's objects (freed on every path, including a throw).
struct Settings {
  gpiod_line_settings* p = gpiod_line_settings_new();
  ~Settings() { gpiod_line_settings_free(p); }
};
struct LineConfig {
  gpiod_line_config* p = gpiod_line_config_new();
  ~LineConfig() { gpiod_line_config_free(p); }
};
struct RequestConfig {
  gpiod_request_config* p = gpiod_request_config_new();
  ~RequestConfig() { gpiod_request_config_free(p); }
};
struct LineInfo {
  gpiod_line_info* p = nullptr;
  ~LineInfo() { gpiod_line_info_free(p); }
};

std::string chip_label(const std::string& path) {
  gpiod_chip* c = gpiod_chip_open(path.c_str());
  if (c == nullptr) return "";
  gpiod_chip_info* info = gpiod_chip_get_info(c);
  std::string label = info != nullptr ? gpiod_chip_info_get_label(info) : "";
  gpiod_chip_info_free(info);
  gpiod_chip_close(c);
  return label;
}

// libgpiod 2 opens paths only; keep 1.6's gpiod_chip_open_lookup rules: a path, a name under
// /dev, a number, or a label.
gpiod_chip* open_chip(const std::string& chip) {
  if (chip.empty()) return nullptr;
  if (chip.front() == '/') return gpiod_chip_open(chip.c_str());
  if (chip.find_first_not_of("0123456789") == std::string::npos) {
    return gpiod_chip_open(("/dev/gpiochip" + chip).c_str());
  }
  const std::string dev = "/dev/" + chip;
  if (gpiod_is_gpiochip_device(dev.c_str())) return gpiod_chip_open(dev.c_str());
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator("/dev", ec)) {
    const std::string p = e.path().string();
    if (p.rfind("/dev/gpiochip", 0) != 0 || !gpiod_is_gpiochip_device(p.c_str())) continue;
    if (chip_label(p) == chip) return gpiod_chip_open(p.c_str());
  }
  errno = ENOENT;
  return nullptr;
}
}  // namespace

struct GpiodBackend::Impl final : GpiodShared {
  explicit Impl(std::span<const AxisLines> lines)
      : GpiodShared(lines),
        out_offset(lines.size(), {-1, -1, -1}),
        enable_offset(lines.size(), -1),
        pump_offset(lines.size(), -1) {}
  ~Impl() override { release(); }  // not copyable: GpiodShared is not

  struct Input {
    gpiod_line_request* req = nullptr;
    std::uint8_t axis = 0;
    InputLine which = InputLine::kCapture;
    unsigned offset = 0;
  };

  gpiod_chip* chip = nullptr;

  gpiod_line_request* out_req = nullptr;                         // all output lines
  std::vector<std::array<int, kOutputLinesPerAxis>> out_offset;  // -1: unwired
  std::vector<unsigned> out_offsets;                             // as requested
  std::vector<int> enable_offset;                                // per axis, -1: none
  std::vector<int> pump_offset;  // per axis (the first's at most), -1: none

  std::vector<Input> inputs;

  // One configured line, claimed (once) and checked before requesting so that the message
  // names the line and its present user.
  void claim_line(unsigned axis, bool input, unsigned line, unsigned offset) {
    claim(axis, input, line, offset);
    LineInfo info{gpiod_chip_get_line_info(chip, offset)};
    if (info.p == nullptr) throw_no_line_info(axis, input, line, offset);
    if (gpiod_line_info_is_used(info.p)) {
      throw_line_busy(axis, input, line, offset, gpiod_line_info_get_consumer(info.p));
    }
  }

  gpiod_line_request* request(gpiod_line_config* lc, const std::string& what) {
    RequestConfig rc;
    gpiod_request_config_set_consumer(rc.p, kGpiodConsumer);
    gpiod_line_request* r = gpiod_chip_request_lines(chip, rc.p, lc);
    if (r == nullptr) throw std::runtime_error(request_error(what));
    return r;
  }

  void add_output(gpiod_line_config* lc, unsigned a, unsigned l, unsigned off,
                  const LineOptions& o) {
    Settings s;
    gpiod_line_settings_set_direction(s.p, GPIOD_LINE_DIRECTION_OUTPUT);
    gpiod_line_settings_set_output_value(s.p, GPIOD_LINE_VALUE_INACTIVE);
    gpiod_line_settings_set_active_low(s.p, o.active_low);
    gpiod_line_settings_set_drive(s.p, kDriveOf.at(static_cast<std::size_t>(o.drive)));
    if (gpiod_line_config_add_line_settings(lc, &off, 1, s.p) != 0) {
      throw std::runtime_error(where(a, false, l, off) +
                               ": line settings: " + std::strerror(errno));
    }
  }
  std::size_t open(const std::string& name) override;
  void claim_axis(unsigned a) override;
  void request_outputs();
  void request_input(Input& in);
  void request_lines() override;
  std::string input_name(const Input& in) const {
    return where(in.axis, true, static_cast<unsigned>(in.which), in.offset);
  }

  void release() noexcept {
    events.reset();  // first: it cancels the reads that use the request fds
    if (out_req != nullptr) {
      for (unsigned o : out_offsets) {
        gpiod_line_request_set_value(out_req, o, GPIOD_LINE_VALUE_INACTIVE);
      }
      gpiod_line_request_release(out_req);
      out_req = nullptr;
    }
    for (Input& in : inputs) {
      if (in.req != nullptr) gpiod_line_request_release(in.req);
      in.req = nullptr;
    }
    if (chip != nullptr) gpiod_chip_close(chip);
    chip = nullptr;
  }
};

void GpiodBackend::Impl::request_outputs() {
  if (out_offsets.empty()) return;
  LineConfig lc;
  for (unsigned a = 0; a < axes.size(); ++a) {
    if (enable_offset[a] >= 0) {
      add_output(lc.p, a, kEnableKeyIndex, static_cast<unsigned>(enable_offset[a]),
                 axes[a].enable_opt);
    }
    if (pump_offset[a] >= 0) {
      add_output(lc.p, a, kChargePumpKeyIndex, static_cast<unsigned>(pump_offset[a]),
                 axes[a].charge_pump_opt);
    }
    for (unsigned l = 0; l < kOutputLinesPerAxis; ++l) {
      if (out_offset[a][l] < 0) continue;
      add_output(lc.p, a, l, static_cast<unsigned>(out_offset[a][l]), axes[a].out_opt[l]);
    }
  }
  out_req = request(lc.p, "GPIO chip '" + chip_name + "': requesting the " +
                              std::to_string(out_offsets.size()) + " output lines");
}

void GpiodBackend::Impl::request_input(Input& in) {
  const LineOptions& o = axes[in.axis].in_opt[static_cast<unsigned>(in.which)];
  const std::string name = where(in.axis, true, static_cast<unsigned>(in.which), in.offset);
  Settings s;
  gpiod_line_settings_set_direction(s.p, GPIOD_LINE_DIRECTION_INPUT);
  gpiod_line_settings_set_edge_detection(s.p, GPIOD_LINE_EDGE_BOTH);
  gpiod_line_settings_set_event_clock(s.p, GPIOD_LINE_CLOCK_MONOTONIC);
  gpiod_line_settings_set_bias(s.p, kBiasOf.at(static_cast<std::size_t>(o.bias)));
  gpiod_line_settings_set_active_low(s.p, o.active_low);
  gpiod_line_settings_set_debounce_period_us(s.p, o.debounce_us);
  LineConfig lc;
  if (gpiod_line_config_add_line_settings(lc.p, &in.offset, 1, s.p) != 0) {
    throw std::runtime_error(name + ": line settings: " + std::strerror(errno));
  }
  in.req = request(lc.p, name + ": requesting edge events");
}

std::size_t GpiodBackend::Impl::open(const std::string& name) {
  chip = open_chip(name);
  if (chip == nullptr) throw_chip_not_found(name);
  gpiod_chip_info* info = gpiod_chip_get_info(chip);
  const std::size_t lines = info != nullptr ? gpiod_chip_info_get_num_lines(info) : 0;
  gpiod_chip_info_free(info);
  return lines;
}

// One axis' lines in configuration order, claimed; requested by request_lines().
void GpiodBackend::Impl::claim_axis(unsigned a) {
  const AxisLines& lines = axes[a];
  for (unsigned l = 0; l < kOutputLinesPerAxis; ++l) {
    if (!lines.out[l]) continue;
    claim_line(a, false, l, *lines.out[l]);
    out_offset[a][l] = static_cast<int>(*lines.out[l]);
    out_offsets.push_back(*lines.out[l]);
  }
  if (lines.enable) {
    claim_line(a, false, kEnableKeyIndex, *lines.enable);
    enable_offset[a] = static_cast<int>(*lines.enable);
    out_offsets.push_back(*lines.enable);
  }
  if (lines.charge_pump) {
    claim_line(a, false, kChargePumpKeyIndex, *lines.charge_pump);
    pump_offset[a] = static_cast<int>(*lines.charge_pump);
    out_offsets.push_back(*lines.charge_pump);
  }
  for (unsigned l = 0; l < kInputLinesPerAxis; ++l) {
    if (!lines.in[l]) continue;
    claim_line(a, true, l, *lines.in[l]);
    in_index[a][l] = static_cast<int>(inputs.size());
    inputs.push_back(
        {nullptr, static_cast<std::uint8_t>(a), static_cast<InputLine>(l), *lines.in[l]});
  }
}

// All outputs in one request; edge events on every claimed input (a request each), and the
// reader of their fds.
void GpiodBackend::Impl::request_lines() {
  request_outputs();
  std::vector<LineEventReader::Source> sources;
  for (Input& in : inputs) {
    request_input(in);
    sources.push_back({gpiod_line_request_get_fd(in.req), in.axis, in.which, input_name(in)});
  }
  start_events(std::move(sources), EdgeRecordFormat::kV2);
}

std::unique_ptr<GpiodShared> GpiodBackend::make_impl(std::span<const AxisLines> lines) {
  return std::make_unique<Impl>(lines);
}

void GpiodBackend::write(unsigned axis, OutputLine line, bool level, Nanos /*t*/) noexcept {
  Impl& d = impl();
  const int off = d.out_offset[axis][static_cast<unsigned>(line)];
  if (off < 0) return;
  if (gpiod_line_request_set_value(d.out_req, static_cast<unsigned>(off),
                                   level ? GPIOD_LINE_VALUE_ACTIVE : GPIOD_LINE_VALUE_INACTIVE) !=
      0) {
    d.count_write_error();
  }
}

bool GpiodBackend::read(unsigned axis, InputLine line) {
  Impl& d = impl();
  const int i = d.input_index(axis, line);
  if (i < 0) return false;
  const Impl::Input& in = d.inputs[static_cast<std::size_t>(i)];
  const gpiod_line_value v = gpiod_line_request_get_value(in.req, in.offset);
  if (v == GPIOD_LINE_VALUE_ERROR) {
    throw std::runtime_error(d.where(axis, true, static_cast<unsigned>(line), in.offset) +
                             ": reading the level: " + std::strerror(errno));
  }
  return v == GPIOD_LINE_VALUE_ACTIVE;
}

namespace {
// A control-thread output (drive enable, charge pump) at `offsets` (by axis; -1: none).
void set_control_line(GpiodShared& d, gpiod_line_request* req, const std::vector<int>& offsets,
                      unsigned axis, bool active) noexcept {
  if (axis >= offsets.size() || offsets[axis] < 0) return;
  if (gpiod_line_request_set_value(req, static_cast<unsigned>(offsets[axis]),
                                   active ? GPIOD_LINE_VALUE_ACTIVE
                                          : GPIOD_LINE_VALUE_INACTIVE) != 0) {
    d.write_errors.fetch_add(1, std::memory_order_relaxed);
  }
}
}  // namespace

void GpiodBackend::set_enable(unsigned axis, bool asserted) noexcept {
  set_control_line(impl(), impl().out_req, impl().enable_offset, axis, asserted);
}

void GpiodBackend::set_charge_pump(unsigned axis, bool active) noexcept {
  set_control_line(impl(), impl().out_req, impl().pump_offset, axis, active);
}

void GpiodBackend::idle_outputs() noexcept {
  Impl& d = impl();
  if (d.out_req == nullptr) return;
  for (unsigned o : d.out_offsets) {
    gpiod_line_request_set_value(d.out_req, o, GPIOD_LINE_VALUE_INACTIVE);
  }
}

}  // namespace stepmod::gpio

#include "gpio/gpiod_backend.hpp"

#include <gpiod.h>
#include <liburing.h>
#include <linux/gpio.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace stepmod::gpio {

namespace {
constexpr const char* kConsumer = "stepmod";
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

  // Outputs: every output line of every axis in one bulk request, so one write is one ioctl
  // (GPIOHANDLE_SET_LINE_VALUES_IOCTL) of the whole shadow array.
  std::vector<std::array<int, kOutputLinesPerAxis>> out_index;  // slot in the bulk, -1 unwired
  gpiod_line_bulk out_bulk{};
  std::vector<int> shadow;
  bool outputs_requested = false;
  std::atomic<std::uint64_t> write_errors{0};

  // Inputs: one event request per line, one io_uring read in flight per line's event fd.
  std::vector<std::array<int, kInputLinesPerAxis>> in_index;  // index into `inputs`, -1 unwired
  std::vector<Input> inputs;
  std::vector<std::array<gpioevent_data, kReadBatch>> bufs;  // never resized after submission
  io_uring ring{};
  bool ring_ready = false;
  std::vector<InputEvent> pending;  // ring buffer of converted events not yet handed out
  std::size_t pending_head = 0, pending_size = 0;
  std::uint64_t lost = 0;

  std::string where(unsigned axis, bool input, unsigned line, unsigned offset) const {
    const std::string_view key =
        input ? input_key(static_cast<InputLine>(line)) : output_key(static_cast<OutputLine>(line));
    return "GPIO chip '" + chip_name + "', line " + std::to_string(offset) + " (axis" +
           std::to_string(axis + 1) + "." + std::string(key) + ")";
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

  void submit_read(std::size_t i) noexcept {
    io_uring_sqe* sqe = io_uring_get_sqe(&ring);
    if (sqe == nullptr) return;  // cannot happen: the SQ has a slot per input
    // Offset -1: "current position"; a line-event fd is a stream and ignores it anyway.
    io_uring_prep_read(sqe, inputs[i].fd, bufs[i].data(), sizeof(bufs[i]), static_cast<__u64>(-1));
    io_uring_sqe_set_data64(sqe, i);
  }

  bool pending_push(const InputEvent& e) noexcept {
    if (pending_size == pending.size()) {
      ++lost;
      return false;
    }
    pending[(pending_head + pending_size) % pending.size()] = e;
    ++pending_size;
    return true;
  }

  std::size_t take_pending(std::span<InputEvent> out) noexcept {
    std::size_t n = 0;
    while (n < out.size() && pending_size > 0) {
      out[n++] = pending[pending_head];
      pending_head = (pending_head + 1) % pending.size();
      --pending_size;
    }
    return n;
  }

  // Converts the completed reads into pending events and puts each read back in flight. A
  // completion is only taken when a whole batch fits, so nothing read is ever dropped here:
  // unreaped completions wait in the CQ and the kernel keeps further edges in its FIFO.
  void reap() {
    io_uring_cqe* cqe = nullptr;
    unsigned resubmit = 0;
    int error = 0;
    std::size_t error_input = 0;
    while (pending.size() - pending_size >= kReadBatch && io_uring_peek_cqe(&ring, &cqe) == 0) {
      const auto i = static_cast<std::size_t>(io_uring_cqe_get_data64(cqe));
      const int res = cqe->res;
      io_uring_cqe_seen(&ring, cqe);
      if (res > 0) {
        const Input& in = inputs[i];
        const std::size_t count = static_cast<std::size_t>(res) / sizeof(gpioevent_data);
        for (std::size_t k = 0; k < count; ++k) {
          const gpioevent_data& ev = bufs[i][k];
          // Since Linux 5.7 ("gpio: Switch timestamps to ktime_get_ns()") the v1 line-event
          // timestamp is CLOCK_MONOTONIC, the clock of every stepmod time (kernel 6.1 here).
          pending_push(InputEvent{static_cast<Nanos>(ev.timestamp), in.axis, in.which,
                                  ev.id == GPIOEVENT_EVENT_RISING_EDGE});
        }
      } else if (res < 0 && res != -EINTR && res != -EAGAIN && res != -ECANCELED) {
        error = -res;
        error_input = i;
      }
      submit_read(i);
      ++resubmit;
    }
    if (resubmit > 0) io_uring_submit(&ring);
    if (error != 0) {
      const Input& in = inputs[error_input];
      throw std::runtime_error(where(in.axis, true, static_cast<unsigned>(in.which), in.offset) +
                               ": reading events: " + std::strerror(error));
    }
  }

  void release() noexcept {
    // The ring first: it cancels the reads that point into `bufs` and at the event fds.
    if (ring_ready) io_uring_queue_exit(&ring);
    ring_ready = false;
    if (outputs_requested) {
      std::fill(shadow.begin(), shadow.end(), 0);
      gpiod_line_set_value_bulk(&out_bulk, shadow.data());
      gpiod_line_release_bulk(&out_bulk);
      outputs_requested = false;
    }
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
      gpiod_line* l = d.get_line(a, input, line, offset);
      const std::string key = "axis" + std::to_string(a + 1) + "." +
                              std::string(input ? input_key(static_cast<InputLine>(line))
                                                : output_key(static_cast<OutputLine>(line)));
      if (!used[offset].empty()) {
        throw std::runtime_error(d.where(a, input, line, offset) + ": offset already used by " +
                                 used[offset]);
      }
      used[offset] = key;
      return l;
    };

    gpiod_line_bulk_init(&d.out_bulk);
    d.out_index.assign(axes.size(), {-1, -1, -1});
    d.in_index.resize(axes.size());
    for (unsigned a = 0; a < axes.size(); ++a) {
      d.in_index[a].fill(-1);
      for (unsigned l = 0; l < kOutputLinesPerAxis; ++l) {
        if (!axes[a].out[l]) continue;
        gpiod_line* line = claim(a, false, l, *axes[a].out[l]);
        d.out_index[a][l] = static_cast<int>(gpiod_line_bulk_num_lines(&d.out_bulk));
        gpiod_line_bulk_add(&d.out_bulk, line);
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

    const unsigned n_out = gpiod_line_bulk_num_lines(&d.out_bulk);
    d.shadow.assign(n_out, 0);
    if (n_out > 0) {
      if (gpiod_line_request_bulk_output(&d.out_bulk, kConsumer, d.shadow.data()) != 0) {
        throw std::runtime_error(d.request_error("GPIO chip '" + chip + "': requesting the " +
                                                 std::to_string(n_out) + " output lines"));
      }
      d.outputs_requested = true;
    }

    for (Impl::Input& in : d.inputs) {
      if (gpiod_line_request_both_edges_events(in.line, kConsumer) != 0) {
        throw std::runtime_error(
            d.request_error(d.where(in.axis, true, static_cast<unsigned>(in.which), in.offset) +
                            ": requesting edge events"));
      }
      in.fd = gpiod_line_event_get_fd(in.line);
    }

    if (!d.inputs.empty()) {
      d.bufs.resize(d.inputs.size());
      d.pending.resize(d.inputs.size() * kReadBatch * 2);
      unsigned entries = 1;
      while (entries < d.inputs.size()) entries <<= 1;
      const int r = io_uring_queue_init(entries, &d.ring, 0);
      if (r < 0) {
        throw std::runtime_error("GPIO chip '" + chip +
                                 "': io_uring_queue_init: " + std::strerror(-r));
      }
      d.ring_ready = true;
      for (std::size_t i = 0; i < d.inputs.size(); ++i) d.submit_read(i);
      const int s = io_uring_submit(&d.ring);
      if (s < 0) {
        throw std::runtime_error("GPIO chip '" + chip + "': io_uring_submit: " + std::strerror(-s));
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
  const int slot = d.out_index[axis][static_cast<unsigned>(line)];
  if (slot < 0) return;
  d.shadow[static_cast<std::size_t>(slot)] = level ? 1 : 0;
  // One ioctl for the whole bulk; the other lines are rewritten with their present values.
  if (gpiod_line_set_value_bulk(&d.out_bulk, d.shadow.data()) != 0) {
    d.write_errors.store(d.write_errors.load(std::memory_order_relaxed) + 1,
                         std::memory_order_relaxed);
  }
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
  if (d.inputs.empty()) {
    sleep_until(deadline);
    return 0;
  }
  for (;;) {
    d.reap();
    const std::size_t n = d.take_pending(out);
    if (n > 0 || out.empty()) return n;
    const Nanos now = monotonic_now();
    if (now >= deadline) return 0;
    const Nanos wait = deadline - now;
    __kernel_timespec ts{};
    ts.tv_sec = wait / kNsPerSec;
    ts.tv_nsec = wait % kNsPerSec;
    io_uring_cqe* cqe = nullptr;
    const int r = io_uring_wait_cqe_timeout(&d.ring, &cqe, &ts);
    if (r == -ETIME) return 0;
    if (r < 0 && r != -EINTR && r != -EAGAIN) {
      throw std::runtime_error("GPIO chip '" + d.chip_name +
                               "': waiting for input events: " + std::strerror(-r));
    }
  }
}

std::uint64_t GpiodBackend::lost_events() const noexcept {
  return d_->lost;
}

std::uint64_t GpiodBackend::write_errors() const noexcept {
  return d_->write_errors.load(std::memory_order_relaxed);
}

void GpiodBackend::idle_outputs() noexcept {
  Impl& d = *d_;
  if (!d.outputs_requested) return;
  std::fill(d.shadow.begin(), d.shadow.end(), 0);
  gpiod_line_set_value_bulk(&d.out_bulk, d.shadow.data());
}

}  // namespace stepmod::gpio

#include "gpio/line_event_reader.hpp"

#include <liburing.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace stepmod::gpio {

struct LineEventReader::Impl {
  std::vector<Source> sources;
  EdgeRecordFormat format = EdgeRecordFormat::kV1;
  std::size_t record_size = 0;
  std::vector<std::vector<std::byte>>
      bufs;                       // kReadBatch records each; never resized after submission
  std::vector<EdgeTrack> tracks;  // per source
  std::vector<bool> open;  // false once a source reported end of file (never for line events)
  io_uring ring{};
  // Converted events not yet handed out (a ring buffer). A completion is reaped only when a
  // whole batch fits, so nothing read is ever dropped: unreaped completions wait in the CQ and
  // the kernel keeps further edges in its FIFO.
  std::vector<InputEvent> pending;
  std::size_t head = 0, size = 0;
  std::uint64_t malformed = 0;
  std::uint64_t lost = 0;

  void submit_read(std::size_t i) noexcept {
    io_uring_sqe* sqe = io_uring_get_sqe(&ring);
    if (sqe == nullptr) return;  // cannot happen: the SQ has a slot per source
    // Offset -1: "current position"; a line-event fd is a stream that ignores it anyway.
    io_uring_prep_read(sqe, sources[i].fd, bufs[i].data(), static_cast<unsigned>(bufs[i].size()),
                       static_cast<__u64>(-1));
    io_uring_sqe_set_data64(sqe, i);
  }

  std::size_t take(std::span<InputEvent> out) noexcept {
    std::size_t n = 0;
    while (n < out.size() && size > 0) {
      out[n++] = pending[head];
      head = (head + 1) % pending.size();
      --size;
    }
    return n;
  }

  void reap() {
    io_uring_cqe* cqe = nullptr;
    unsigned resubmit = 0;
    int error = 0;
    std::size_t error_source = 0;
    while (pending.size() - size >= kReadBatch && io_uring_peek_cqe(&ring, &cqe) == 0) {
      const auto i = static_cast<std::size_t>(io_uring_cqe_get_data64(cqe));
      const int res = cqe->res;
      io_uring_cqe_seen(&ring, cqe);
      if (res > 0) {
        const std::size_t count = static_cast<std::size_t>(res) / record_size;
        if (static_cast<std::size_t>(res) % record_size != 0) ++malformed;
        for (std::size_t k = 0; k < count; ++k) {
          const DecodedEdge ev =
              decode_edge_record(format, bufs[i].data() + k * record_size, tracks[i]);
          lost += ev.lost;
          pending[(head + size) % pending.size()] =
              InputEvent{ev.t, sources[i].axis, sources[i].line, ev.level};
          ++size;
        }
      } else if (res == 0) {
        open[i] = false;  // end of file: nothing more will come from this source
        continue;
      } else if (res != -EINTR && res != -EAGAIN && res != -ECANCELED) {
        error = -res;
        error_source = i;
        open[i] = false;
        continue;
      }
      submit_read(i);
      ++resubmit;
    }
    if (resubmit > 0) io_uring_submit(&ring);
    if (error != 0) {
      throw std::runtime_error(sources[error_source].name +
                               ": reading input events: " + std::strerror(error));
    }
  }
};

LineEventReader::LineEventReader(std::vector<Source> sources, EdgeRecordFormat format)
    : d_(std::make_unique<Impl>()) {
  Impl& d = *d_;
  d.sources = std::move(sources);
  d.format = format;
  d.record_size = edge_record_size(format);
  d.bufs.assign(d.sources.size(), std::vector<std::byte>(kReadBatch * d.record_size));
  d.tracks.assign(d.sources.size(), EdgeTrack{});
  d.open.assign(d.sources.size(), true);
  d.pending.resize(std::max<std::size_t>(d.sources.size(), 1) * kReadBatch * 2);
  unsigned entries = 1;
  while (entries < d.sources.size()) entries <<= 1;
  const int r = io_uring_queue_init(entries, &d.ring, 0);
  if (r < 0) {
    d_.reset();
    throw std::runtime_error(std::string("io_uring_queue_init: ") + std::strerror(-r));
  }
  for (std::size_t i = 0; i < d.sources.size(); ++i) d.submit_read(i);
  const int s = io_uring_submit(&d.ring);
  if (s < 0) {
    io_uring_queue_exit(&d.ring);
    d_.reset();
    throw std::runtime_error(std::string("io_uring_submit: ") + std::strerror(-s));
  }
}

LineEventReader::~LineEventReader() {
  // Closing the ring cancels the reads in flight, which point into `bufs` and at the fds.
  if (d_) io_uring_queue_exit(&d_->ring);
}

std::uint64_t LineEventReader::malformed() const noexcept {
  return d_->malformed;
}

std::uint64_t LineEventReader::lost() const noexcept {
  return d_->lost;
}

std::size_t LineEventReader::wait(std::span<InputEvent> out, Nanos deadline) {
  Impl& d = *d_;
  for (;;) {
    d.reap();
    const std::size_t n = d.take(out);
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
      throw std::runtime_error(std::string("waiting for input events: ") + std::strerror(-r));
    }
  }
}

}  // namespace stepmod::gpio

#include "gpio/trace_spool.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "gpio/trace_file.hpp"

namespace stepmod::gpio {

namespace {
constexpr std::size_t kWriteBuffer = std::size_t{1} << 18;  // records: 4 MB per write
constexpr std::size_t kReadBatch = std::size_t{1} << 16;
constexpr char kMagic[8] = {'S', 'M', 'S', 'P', 'O', 'O', 'L', '1'};

struct Header {
  char magic[8];
  std::int64_t start;
  std::uint32_t wires;
  std::uint32_t record_size;
};

// write() all of `n` bytes; false (errno set) on an error or a short write that cannot go on.
bool write_all(int fd, const void* data, std::size_t n) noexcept {
  const auto* p = static_cast<const char*>(data);
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) {
      if (w == 0) errno = ENOSPC;
      return false;
    }
    p += w;
    n -= static_cast<std::size_t>(w);
  }
  return true;
}
}  // namespace

bool SpoolInfo::operator==(const SpoolInfo& o) const {
  if (start != o.start || wires.size() != o.wires.size()) return false;
  for (std::size_t i = 0; i < wires.size(); ++i) {
    const TraceWire& a = wires[i];
    const TraceWire& b = o.wires[i];
    if (a.axis != b.axis || a.is_input != b.is_input || a.line != b.line ||
        a.initial != b.initial || a.active_low != b.active_low) {
      return false;
    }
  }
  return true;
}

TraceSpool::TraceSpool(std::string path, const SpoolInfo& info)
    : path_(std::move(path)), buffer_(kWriteBuffer) {
  try {
    fd_ = create_new_file(path_, "trace spool");
  } catch (const std::runtime_error& e) {
    // A regular file there is most likely a killed daemon's spool: never overwritten.
    throw std::runtime_error(std::string(e.what()) +
                             "; not overwritten (a spool left by a daemon that did not stop? "
                             "stepmodctl trace recover, or remove it)");
  }
  Header h{};
  std::memcpy(h.magic, kMagic, sizeof kMagic);
  h.start = info.start;
  h.wires = static_cast<std::uint32_t>(info.wires.size());
  h.record_size = sizeof(TraceRecord);
  if (!write_all(fd_, &h, sizeof h) ||
      !write_all(fd_, info.wires.data(), info.wires.size() * sizeof(TraceWire))) {
    const std::string why = std::strerror(errno);
    ::close(fd_);
    ::unlink(path_.c_str());
    throw std::runtime_error("trace spool '" + path_ + "': cannot write: " + why);
  }
}

TraceSpool::~TraceSpool() {
  if (!keep_) remove();
  if (fd_ >= 0) ::close(fd_);
}

void TraceSpool::remove() noexcept {
  if (fd_ < 0) return;
  ::close(fd_);
  fd_ = -1;
  ::unlink(path_.c_str());
}

void TraceSpool::append(const TraceRecord& r) noexcept {
  ++count_;
  if (failed()) return;
  buffer_[used_++] = r;
  if (used_ == buffer_.size()) flush();
}

bool TraceSpool::flush() noexcept {
  if (failed()) return false;
  if (used_ == 0) return true;
  const std::size_t n = used_;
  used_ = 0;
  if (!write_all(fd_, buffer_.data(), n * sizeof(TraceRecord))) {
    error_ = errno;
    failed_.store(true, std::memory_order_release);
    return false;
  }
  written_ += n;
  return true;
}

// ---- reading ------------------------------------------------------------------------------------

SpoolReader::SpoolReader(int fd, std::string name) : name_(std::move(name)), buf_(kReadBatch) {
  fd_ = ::dup(fd);
  if (fd_ < 0) throw std::runtime_error("trace spool '" + name_ + "': " + std::strerror(errno));
  read_header();
}

SpoolReader::SpoolReader(const std::string& path) : name_(path), buf_(kReadBatch) {
  fd_ = open_regular_for_reading(path, "trace spool");
  read_header();
}

SpoolReader::~SpoolReader() {
  if (fd_ >= 0) ::close(fd_);
}

void SpoolReader::read_header() {
  Header h{};
  const auto fail = [&](const std::string& why) {
    ::close(fd_);
    fd_ = -1;
    throw std::runtime_error("trace spool '" + name_ + "': " + why);
  };
  if (::pread(fd_, &h, sizeof h, 0) != static_cast<ssize_t>(sizeof h) ||
      std::memcmp(h.magic, kMagic, sizeof kMagic) != 0 || h.record_size != sizeof(TraceRecord) ||
      h.wires > 4096) {
    fail("not a stepmod trace spool (or its header is cut short)");
  }
  info_.start = h.start;
  info_.wires.resize(h.wires);
  const std::size_t bytes = h.wires * sizeof(TraceWire);
  if (::pread(fd_, info_.wires.data(), bytes, sizeof h) != static_cast<ssize_t>(bytes)) {
    fail("its header is cut short");
  }
  offset_ = sizeof h + bytes;
}

const TraceRecord* SpoolReader::next() {
  if (pos_ == len_) {
    const ssize_t n =
        ::pread(fd_, buf_.data(), buf_.size() * sizeof(TraceRecord), static_cast<off_t>(offset_));
    if (n < 0) throw std::runtime_error("trace spool '" + name_ + "': " + std::strerror(errno));
    len_ = static_cast<std::size_t>(n) / sizeof(TraceRecord);
    offset_ += len_ * sizeof(TraceRecord);
    pos_ = 0;
    if (len_ == 0) return nullptr;
  }
  return &buf_[pos_++];
}

// ---- ordering -----------------------------------------------------------------------------------

OrderedReader::OrderedReader(SpoolReader& source, std::size_t window)
    : source_(source), window_(std::max<std::size_t>(window, 1)) {}

const TraceRecord* OrderedReader::next() {
  while (!source_done_ && pending_.size() < window_) {
    const TraceRecord* r = source_.next();
    if (r == nullptr) {
      source_done_ = true;
      break;
    }
    pending_.push_back(*r);
    // Back past every later record (strictly: equal times keep their file order).
    for (std::size_t k = pending_.size() - 1; k > 0 && pending_[k - 1].t > pending_[k].t; --k) {
      std::swap(pending_[k - 1], pending_[k]);
    }
  }
  if (pending_.empty()) return nullptr;
  current_ = pending_.front();
  pending_.pop_front();
  return &current_;
}

}  // namespace stepmod::gpio

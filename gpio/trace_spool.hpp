#pragma once
// A binary spool of TraceRecords: the trace thread appends what it drains from a trace ring
// (a buffered write of 16-byte records, tens of millions a second), and the VCD is written from
// it when the daemon stops. Formatting text while the pulse thread produces 2 M records/s is what
// made the old streaming writer fall behind and its ring overflow (issue 12: a third of a 1 MHz
// move lost).
//
// A spool starts with a header (the VCD's #0 time and its wires), so that the spools a killed
// daemon left behind can still be turned into a VCD (`stepmodctl trace recover`). Files are
// created new and read back through their own descriptor (gpio/trace_file.hpp).
#include <atomic>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "core/trace_record.hpp"

namespace stepmod::gpio {

// One traced line and its level at #0.
struct TraceWire {
  std::uint8_t axis = 0;  // 0-based; the wire is named axis<axis+1>.<key>
  bool is_input = false;
  std::uint8_t line = 0;    // OutputLine or InputLine value
  bool initial = false;     // logical level at the start
  bool active_low = false;  // the wire carries the inverse of the logical level
};

// What a spool's header holds: enough to write the VCD's header.
struct SpoolInfo {
  Nanos start = 0;  // CLOCK_MONOTONIC time that is #0
  std::vector<TraceWire> wires;
  bool operator==(const SpoolInfo& o) const;
};

class TraceSpool {
 public:
  // Creates `path` as a new file (never an existing name) and writes the header; throws
  // std::runtime_error naming it if that fails.
  TraceSpool(std::string path, const SpoolInfo& info);
  ~TraceSpool();  // closes the file and removes it unless keep() was called
  TraceSpool(const TraceSpool&) = delete;
  TraceSpool& operator=(const TraceSpool&) = delete;

  // Buffers one record; a full buffer is written. After a failed write nothing more is written
  // (the file stays a valid prefix) and failed() is true.
  void append(const TraceRecord& r) noexcept;
  // Writes the buffer; false if this or any earlier write failed (disk full...).
  bool flush() noexcept;
  // Any thread: whether a write failed (the daemon's health bit 4), and its errno.
  bool failed() const noexcept { return failed_.load(std::memory_order_acquire); }
  int error() const noexcept { return error_; }
  // Records appended (written or not).
  std::uint64_t size() const noexcept { return count_; }
  // Records in the file.
  std::uint64_t written() const noexcept { return written_; }
  // Leave the file behind when destroyed (the VCD could not be written from it).
  void keep() noexcept { keep_ = true; }
  // Closes and removes the file now (its records are in the VCD).
  void remove() noexcept;
  int fd() const noexcept { return fd_; }
  const std::string& path() const noexcept { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
  std::vector<TraceRecord> buffer_;
  std::size_t used_ = 0;
  std::uint64_t count_ = 0;
  std::uint64_t written_ = 0;
  std::atomic<bool> failed_{false};
  int error_ = 0;
  bool keep_ = false;
};

// Reads a spool back: its header, then its records in file order. A trailing partial record (a
// write cut short by a full disk or a kill) is ignored.
class SpoolReader {
 public:
  // Through a descriptor of its own (dup'ed from `fd`, read with pread): the writer's file.
  SpoolReader(int fd, std::string name);
  // A spool by name (stepmodctl trace recover): a regular file only, never a link or FIFO.
  explicit SpoolReader(const std::string& path);
  ~SpoolReader();
  SpoolReader(const SpoolReader&) = delete;
  SpoolReader& operator=(const SpoolReader&) = delete;

  const SpoolInfo& info() const noexcept { return info_; }
  // The next record, or nullptr at the end. Throws std::runtime_error on a read error.
  const TraceRecord* next();

 private:
  void read_header();

  int fd_ = -1;
  std::string name_;
  SpoolInfo info_;
  std::uint64_t offset_ = 0;
  std::vector<TraceRecord> buf_;
  std::size_t pos_ = 0;
  std::size_t len_ = 0;
};

// A spool's records in time order. The records of one spool are only nearly ordered: the input
// spool interleaves the edges of several lines (and axes), each in order, as the control thread
// happened to collect them (a 3202's two encoders: 5-7 % of the input records were behind one of
// the other axis). Each record read is moved back past the later ones among the last `window`
// records not yet given out (an insertion sort: a pass-through for records in order, a few moves
// for the nearly ordered); a record more than `window` records away from its place stays late
// (VcdTrace::late() counts it).
class OrderedReader {
 public:
  static constexpr std::size_t kWindow = std::size_t{1} << 16;
  explicit OrderedReader(SpoolReader& source, std::size_t window = kWindow);
  const TraceRecord* next();

 private:
  SpoolReader& source_;
  std::size_t window_;
  std::deque<TraceRecord> pending_;  // in time order; given out from the front
  bool source_done_ = false;
  TraceRecord current_;
};

}  // namespace stepmod::gpio

#pragma once
// The `--trace FILE.vcd` writer (INTERFACE.md section 5).
//
//   VcdTrace    - the file: header, one 1-bit wire per configured line named axis<N>.<key>,
//                 initial values at #0, value changes in ns relative to the daemon's start.
//   TraceMerger - the time-ordering window, without any thread (unit-testable): records from the
//                 two rings are each in time order but may interleave late by a few ms, so they
//                 are held until they are older than `window` and then emitted sorted.
//   TraceWriter - the trace thread: drains the pulse thread's ring (outputs) and the control
//                 thread's ring (inputs) through a TraceMerger into a VcdTrace.
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <queue>
#include <span>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "core/spsc_ring.hpp"
#include "core/trace_record.hpp"
#include "gpio/backend.hpp"

namespace stepmod::gpio {

// One traced line and its level at #0.
struct TraceWire {
  std::uint8_t axis = 0;  // 0-based; the wire is named axis<axis+1>.<key>
  bool is_input = false;
  std::uint8_t line = 0;  // OutputLine or InputLine value
  bool initial = false;
};

// Every configured line of `backend`: outputs start low (the daemon idles them before starting),
// inputs at their present level.
std::vector<TraceWire> trace_wires(Backend& backend);

// The VCD name of a line: "axis1.step", "axis2.cw_limit", ...
std::string wire_name(const TraceWire& w);

class VcdTrace {
 public:
  // Opens (truncates) `path` and writes the header and the #0 values; throws std::runtime_error
  // naming the file if it cannot be opened. `start`: CLOCK_MONOTONIC time that is #0.
  VcdTrace(const std::string& path, std::span<const TraceWire> wires, Nanos start);
  ~VcdTrace();  // closes, ignoring errors (call close() to see them)
  VcdTrace(const VcdTrace&) = delete;
  VcdTrace& operator=(const VcdTrace&) = delete;

  // Writes one change. A record for a line not in the file is counted in unknown(); a record
  // that does not change its line's level writes nothing (VCD holds changes). A record older
  // than the last written time (later than the merge window allowed) is written at that time,
  // so the file stays valid, and counted in late().
  void record(const TraceRecord& r);
  void comment(std::string_view text);
  // Writes a final timestamp `end` (if later than the last change) so viewers show the whole
  // run, flushes and closes. Throws std::runtime_error if the file could not be written.
  void close(Nanos end);
  void flush();

  std::uint64_t late() const noexcept { return late_; }
  std::uint64_t unknown() const noexcept { return unknown_; }
  std::uint64_t changes() const noexcept { return changes_; }

 private:
  int wire_index(const TraceRecord& r) const noexcept;

  std::string path_;
  std::FILE* f_ = nullptr;
  Nanos start_ = 0;
  Nanos last_ = 0;  // last written time, relative
  std::vector<TraceWire> wires_;
  std::vector<std::string> ids_;
  std::vector<std::uint8_t> levels_;
  std::vector<int> index_;  // (axis * 2 + is_input) * 16 + line -> wire, -1 if absent
  std::uint64_t late_ = 0, unknown_ = 0, changes_ = 0;
};

// The merge window. add() in any order; release() hands out, in (time, arrival) order, every
// record with t < cut. Not thread-safe: used by the trace thread only.
class TraceMerger {
 public:
  void add(const TraceRecord& r) { heap_.push(Held{r, seq_++}); }
  template <typename Sink>
  void release(Nanos cut, Sink&& sink) {
    while (!heap_.empty() && heap_.top().r.t < cut) {
      sink(heap_.top().r);
      heap_.pop();
    }
  }
  template <typename Sink>
  void release_all(Sink&& sink) {
    while (!heap_.empty()) {
      sink(heap_.top().r);
      heap_.pop();
    }
  }
  std::size_t held() const noexcept { return heap_.size(); }

 private:
  struct Held {
    TraceRecord r;
    std::uint64_t seq;
    // priority_queue is a max-heap: "less" means later.
    bool operator<(const Held& o) const noexcept {
      return r.t != o.r.t ? r.t > o.r.t : seq > o.seq;
    }
  };
  std::priority_queue<Held> heap_;
  std::uint64_t seq_ = 0;
};

class TraceWriter {
 public:
  // Opens the VCD (see VcdTrace). `outputs`: the pulse thread's trace ring; `inputs`: the control
  // thread's. Both must outlive the writer. `window`: how late a record may arrive relative to
  // the other ring and still be sorted in; `period`: how often the thread drains the rings.
  TraceWriter(const std::string& path, std::span<const TraceWire> wires, Nanos start,
              SpscRing<TraceRecord>& outputs, SpscRing<TraceRecord>& inputs,
              Nanos window = 50 * kNsPerMs, Nanos period = 5 * kNsPerMs);
  ~TraceWriter();  // stop() if still running (without dropped counts)
  TraceWriter(const TraceWriter&) = delete;
  TraceWriter& operator=(const TraceWriter&) = delete;

  void start();
  // Stops the thread (after the producers have stopped), writes every record still in the rings
  // or the window, a $comment with the producers' dropped-record counts, and closes the file.
  // Throws std::runtime_error if the file could not be written.
  void stop(std::uint64_t dropped_outputs = 0, std::uint64_t dropped_inputs = 0);

  // One round of the thread's work at time `now` (tests call it without the thread).
  void step(Nanos now);

  VcdTrace& vcd() noexcept { return vcd_; }
  const TraceMerger& merger() const noexcept { return merger_; }

 private:
  void run();
  void drain();

  VcdTrace vcd_;
  SpscRing<TraceRecord>& outputs_;
  SpscRing<TraceRecord>& inputs_;
  const Nanos window_;
  const Nanos period_;
  TraceMerger merger_;
  std::thread thread_;
  std::atomic<bool> running_{false};
  bool closed_ = false;
  Nanos last_flush_ = 0;
};

}  // namespace stepmod::gpio

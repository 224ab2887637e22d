#pragma once
// The `--trace FILE.vcd` writer (docs/interface.md section 5).
//
//   VcdTrace    - the file: header, one 1-bit wire per configured line named axis<N>.<key>,
//                 initial values at #0, value changes in ns relative to the daemon's start.
//   TraceWriter - the trace thread: drains the pulse thread's ring (outputs) and the control
//                 thread's ring (inputs) into binary spools, and writes the VcdTrace from them
//                 when it stops.
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "core/spsc_ring.hpp"
#include "core/trace_record.hpp"
#include "gpio/backend.hpp"
#include "gpio/trace_file.hpp"
#include "gpio/trace_spool.hpp"

namespace stepmod::gpio {

// Every configured line of `backend`: outputs start low (the daemon idles them before starting),
// inputs at their present level. The VCD shows wire levels: an active-low line's inverted.
std::vector<TraceWire> trace_wires(Backend& backend);

// The drive-enable output (an extension, written by the control thread, not the pulse thread)
// is traced as one more output line of its axis: TraceRecord::line kEnableTraceLine, is_input 0,
// wire "axis<N>.enable". Its records go through the control thread's (input) ring, whose stream
// the writer orders by time like the input edges.
inline constexpr std::uint8_t kEnableTraceLine = kOutputLinesPerAxis;
// The enable wire of `axis`, released (logically low) at #0: the daemon releases it at start.
TraceWire enable_trace_wire(unsigned axis, bool active_low);
// The module's charge pump (an extension, written by the control thread) likewise: line
// kChargePumpTraceLine of the module's first axis, wire "charge_pump", inactive at #0.
inline constexpr std::uint8_t kChargePumpTraceLine = kOutputLinesPerAxis + 1;
TraceWire charge_pump_trace_wire(unsigned first_axis, bool active_low);

// The VCD name of a line: "axis1.step", "axis2.cw_limit", "axis1.enable", ...; with
// `axis_names` (a rack, docs/interface.md section 7: by trace axis, "x.axis1") the axis part is
// its name: "x.axis1.step". The charge pump is the module's: "charge_pump", in a rack
// "x.charge_pump" (without names, on a module's first axis past the rack's first:
// "axis3.charge_pump").
std::string wire_name(const TraceWire& w, std::span<const std::string> axis_names = {});

class VcdTrace {
 public:
  // Writes the header and the #0 values to a new file beside `path` (gpio/trace_file.hpp),
  // which close() renames to `path` (replacing the name, whatever it is: a link planted there is
  // never followed); throws std::runtime_error naming the file if it cannot be created.
  // `start`: CLOCK_MONOTONIC time that is #0.
  // `loss_marker`: also declare the wire kLossMarkerWire, driven by kLossMarker records.
  // `axis_names`: as wire_name's.
  VcdTrace(const std::string& path, std::span<const TraceWire> wires, Nanos start,
           bool loss_marker = false, std::vector<std::string> axis_names = {});
  ~VcdTrace();  // as close() if still open, ignoring errors (a failed file is removed)
  VcdTrace(const VcdTrace&) = delete;
  VcdTrace& operator=(const VcdTrace&) = delete;

  // Writes one change. A record for a line not in the file is counted in unknown(); a record
  // that does not change its line's level writes nothing (VCD holds changes). A record older
  // than the last written time (later than the merge window allowed) is written at that time,
  // so the file stays valid, and counted in late().
  void record(const TraceRecord& r);
  void comment(std::string_view text);
  // Writes a final timestamp `end` (if later than the last change) so viewers show the whole
  // run, flushes, closes and renames the file into place. Throws std::runtime_error if the file
  // could not be written (it is then removed; whatever was at `path` stays as it was).
  void close(Nanos end);
  // Closes and removes the unfinished file; `path` is left as it was.
  void abandon() noexcept;
  void flush();
  // CLOCK_MONOTONIC time of the last change written (start if none).
  Nanos last_time() const noexcept { return start_ + last_; }

  std::uint64_t late() const noexcept { return late_; }
  std::uint64_t unknown() const noexcept { return unknown_; }
  std::uint64_t changes() const noexcept { return changes_; }

 private:
  int wire_index(const TraceRecord& r) const noexcept;

  std::string path_;
  NewFile file_;  // the new file (gpio/trace_file.hpp), put in place at path_ by close()
  std::FILE* f_ = nullptr;
  Nanos start_ = 0;
  Nanos last_ = 0;  // last written time, relative
  std::vector<TraceWire> wires_;
  std::vector<std::string> axis_names_;
  std::vector<std::string> ids_;
  std::vector<std::uint8_t> levels_;
  std::vector<int> index_;  // (axis * 2 + is_input) * 16 + line -> wire, -1 if absent
  int marker_ = -1;         // wire of the loss marker, -1 if not declared
  std::uint64_t late_ = 0, unknown_ = 0, changes_ = 0;
};

// TraceRecord::is_input value of a loss marker (not a line): records were lost just after `t`.
inline constexpr std::uint8_t kLossMarker = 2;
inline constexpr const char* kLossMarkerWire = "trace.records_lost";

// The trace thread. While the daemon runs it only moves records from the two rings (outputs of
// the pulse thread, inputs of the control thread) into two binary spools (gpio/trace_spool.hpp),
// which keeps up with 2 M records/s with CPU to spare; stop() writes the VCD from them, merging
// the two time-ordered streams. Records the producers could not push (ring full) are counted by
// them; the thread watches those counters and puts a loss marker where records went missing, and
// the VCD then declares the marker wire `trace.records_lost` (a pulse at each loss) and says so
// in a comment.
// What stop() did, for the daemon's log and exit status.
struct TraceOutcome {
  bool complete = true;     // every record is in the VCD
  bool vcd_written = true;  // the VCD is at its path (else the spools were kept beside it)
  std::string problem;      // what went wrong, "" when complete
};

// The streams of `readers` (each in time order) merged into `vcd`; equal times go in the order
// of `readers`.
void write_merged(std::span<OrderedReader* const> readers, VcdTrace& vcd);

class TraceWriter {
 public:
  // Refuses a `path` that exists and is not a regular file, and creates the spools beside it as
  // new files (`path`.out.spool / .in.spool; an existing name is refused: a killed daemon's
  // spools are recovered with `stepmodctl trace recover` or removed first). Removed by stop()
  // once the VCD is written. Throws std::runtime_error naming the file.
  // Both rings must outlive the writer. `period`: how often the thread drains the rings.
  TraceWriter(const std::string& path, std::span<const TraceWire> wires, Nanos start,
              SpscRing<TraceRecord>& outputs, SpscRing<TraceRecord>& inputs,
              Nanos period = 5 * kNsPerMs);
  ~TraceWriter();  // stop() if still running (without dropped counts)
  TraceWriter(const TraceWriter&) = delete;
  TraceWriter& operator=(const TraceWriter&) = delete;

  // The producers' counters of records lost because a ring was full (either may be null).
  // Call before start().
  void watch_losses(const std::atomic<std::uint64_t>* outputs,
                    const std::atomic<std::uint64_t>* inputs) noexcept {
    lost_outputs_ = outputs;
    lost_inputs_ = inputs;
  }

  // The wires' axis names (wire_name; a rack's). Call before start().
  void name_axes(std::vector<std::string> names) { axis_names_ = std::move(names); }

  // Starts the thread. `fifo_priority` > 0: the thread asks for SCHED_FIFO at that priority
  // (the daemon: 1, below every other real-time thread but above all normal ones), so that a
  // loaded machine cannot starve it for the seconds it takes to fill a ring at 2 M records/s;
  // its work is a copy every `period`. Refused (no privilege): it runs as a normal thread, and
  // fifo() says so.
  void start(int fifo_priority = 0);
  bool fifo() const noexcept { return fifo_.load(std::memory_order_acquire); }
  // Stops the thread (after the producers have stopped), spools what is left in the rings and
  // writes the VCD: every record in time order, a $comment with the producers' dropped-record
  // counts, and with any loss (or a spool write that failed) the marker wire and a
  // "TRACE INCOMPLETE" comment. A VCD that cannot be written (a full disk) is not left half
  // written: the spools stay beside its path instead, and the outcome says so. Never throws.
  TraceOutcome stop(std::uint64_t dropped_outputs = 0, std::uint64_t dropped_inputs = 0);

  // Any thread: a spool write failed (disk full...): the trace is incomplete from then on.
  bool failed() const noexcept { return out_spool_.failed() || in_spool_.failed(); }

  // One round of the thread's work: drain both rings into the spools (tests call it without
  // the thread).
  void step();

  // Records spooled so far (any thread: for diagnostics and the trace benchmark).
  std::uint64_t spooled() const noexcept { return spooled_.load(std::memory_order_relaxed); }
  // The written file's statistics; valid after a stop() that wrote it.
  const VcdTrace& vcd() const { return *vcd_; }
  // How often the thread writes the spools' buffers to their files: what a killed daemon loses.
  static constexpr Nanos kFlushPeriod = 100 * kNsPerMs;

 private:
  void run();
  void drain(SpscRing<TraceRecord>& ring, TraceSpool& spool, const std::atomic<std::uint64_t>* lost,
             std::uint64_t& lost_seen, Nanos& last_t);
  void write_vcd(std::uint64_t dropped_outputs, std::uint64_t dropped_inputs);
  TraceOutcome finish(std::uint64_t dropped_outputs, std::uint64_t dropped_inputs);

  std::string path_;
  std::vector<TraceWire> wires_;
  std::vector<std::string> axis_names_;
  Nanos start_;
  SpscRing<TraceRecord>& outputs_;
  SpscRing<TraceRecord>& inputs_;
  const Nanos period_;
  TraceSpool out_spool_;
  TraceSpool in_spool_;
  const std::atomic<std::uint64_t>* lost_outputs_ = nullptr;
  const std::atomic<std::uint64_t>* lost_inputs_ = nullptr;
  std::uint64_t lost_outputs_seen_ = 0;
  std::uint64_t lost_inputs_seen_ = 0;
  Nanos last_output_t_ = 0;
  Nanos last_input_t_ = 0;
  std::uint64_t markers_ = 0;
  std::atomic<std::uint64_t> spooled_{0};
  std::unique_ptr<VcdTrace> vcd_;
  std::thread thread_;
  std::atomic<bool> running_{false};
  std::atomic<bool> fifo_{false};
  bool closed_ = false;
  TraceOutcome outcome_;
};

}  // namespace stepmod::gpio

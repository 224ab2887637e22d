#pragma once
// stepmodd --trace: the VCD of every output and input edge (docs/traces.md), of every module of
// the rack, on the step output's axis numbers (a module's axis a is its first_axis + a). Two
// record rings: the outputs from the pulse thread (the step output writes them), the inputs and
// the drive enables from the modules' control threads (record_input, one at a time). The trace
// thread (gpio::TraceWriter) spools both as they fill and writes the VCD when the daemon stops;
// it puts the control threads' records in time order (gpio::OrderedReader).
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "core/spsc_ring.hpp"
#include "core/trace_record.hpp"
#include "gpio/vcd_trace.hpp"

namespace stepmod::tools {

class Stack;

// One module's way into the rack's trace: its records on the trace's axis numbers. Its control
// thread.
class ModuleTrace;

class DaemonTrace {
 public:
  // Main thread. The rings only: the stack, built next, is handed the output ring.
  DaemonTrace();
  ~DaemonTrace();
  DaemonTrace(const DaemonTrace&) = delete;
  DaemonTrace& operator=(const DaemonTrace&) = delete;

  SpscRing<TraceRecord>* output_ring() noexcept { return output_.get(); }
  // Main thread, once the stack exists: the writer of `path` with a wire for every configured
  // line, drive enable and charge pump; #0 is `start` (CLOCK_MONOTONIC).
  // `rack_file`: the wires are named after their modules ("x.axis1.step"; docs/interface.md
  // section 7), as in a rack file, else as of a lone module (section 5: "axis1.step").
  void open(const std::string& path, Nanos start, std::span<const Config> modules, bool rack_file,
            Stack& stack);
  // Main thread, before the pulse thread.
  void start_thread();

  // A control thread (or, once they have ended, the main thread): one record into the input
  // ring, whose producers take turns. A full ring counts a loss.
  void record_input(const TraceRecord& r) noexcept;
  // A control thread, per scan: whether records are lost (a ring was full, or a spool write
  // failed: health bit 4 from then on); the first time, says so in the log.
  bool lost();
  // Main thread, after the pulse thread has been joined (this thread may now produce into the
  // output ring too): the outputs the daemon has just idled, as the lines' last changes.
  void record_idle_outputs(Stack& stack, Nanos now) noexcept;
  // Main thread, after every thread: the VCD written; false if it lost records.
  bool finish();

 private:
  std::uint64_t dropped() const noexcept;
  static std::vector<std::string> axis_names(std::span<const Config> modules, Stack& stack);

  std::unique_ptr<SpscRing<TraceRecord>> output_;
  std::unique_ptr<SpscRing<TraceRecord>> input_;
  std::mutex input_producer_;  // the control threads take turns at the input ring
  std::atomic<std::uint64_t> input_dropped_{
      0};  // the control threads write, the trace thread reads
  const std::atomic<std::uint64_t>* output_dropped_ = nullptr;  // the step output's counter
  std::unique_ptr<gpio::TraceWriter> writer_;  // after the rings: stopped before they go
  std::atomic<bool> loss_logged_{false};
};

class ModuleTrace {
 public:
  ModuleTrace(DaemonTrace& trace, unsigned first_axis) noexcept
      : trace_(trace), first_axis_(static_cast<std::uint8_t>(first_axis)) {}
  // `r` with the module's own axis number.
  void record_input(TraceRecord r) noexcept {
    r.axis = static_cast<std::uint8_t>(r.axis + first_axis_);
    trace_.record_input(r);
  }
  bool lost() { return trace_.lost(); }

 private:
  DaemonTrace& trace_;
  std::uint8_t first_axis_;
};

}  // namespace stepmod::tools

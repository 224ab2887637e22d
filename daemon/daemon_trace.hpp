#pragma once
// stepmodd --trace: the VCD of every output and input edge (docs/traces.md). Two record rings,
// each with one producer: the outputs from the pulse thread (the step output writes them), the
// inputs and the drive enables from the control thread (record_input). The trace thread
// (gpio::TraceWriter) spools both as they fill and writes the VCD when the daemon stops.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "config/config.hpp"
#include "core/spsc_ring.hpp"
#include "core/trace_record.hpp"
#include "gpio/vcd_trace.hpp"

namespace stepmod::tools {

class Stack;

class DaemonTrace {
 public:
  // Main thread. The rings only: the stack, built next, is handed the output ring.
  DaemonTrace();
  ~DaemonTrace();
  DaemonTrace(const DaemonTrace&) = delete;
  DaemonTrace& operator=(const DaemonTrace&) = delete;

  SpscRing<TraceRecord>* output_ring() noexcept { return output_.get(); }
  // Main thread, once the stack exists: the writer of `path` with a wire for every configured
  // line and drive enable; #0 is `start` (CLOCK_MONOTONIC).
  void open(const std::string& path, Nanos start, const Config& config, Stack& stack);
  // Main thread, before the pulse thread.
  void start_thread();

  // Control thread (or, once it has ended, the thread that ran it): one record into the input
  // ring, whose only producer that thread is. A full ring counts a loss.
  void record_input(const TraceRecord& r) noexcept;
  // Control thread, per scan: whether records are lost (a ring was full, or a spool write
  // failed: health bit 4 from then on); the first time, says so in the log.
  bool lost();
  // Main thread, after the pulse thread has been joined (this thread may now produce into the
  // output ring too): the outputs the daemon has just idled, as the lines' last changes.
  void record_idle_outputs(const Stack& stack, Nanos now) noexcept;
  // Main thread, after every thread: the VCD written; false if it lost records.
  bool finish();

 private:
  std::uint64_t dropped() const noexcept;

  std::unique_ptr<SpscRing<TraceRecord>> output_;
  std::unique_ptr<SpscRing<TraceRecord>> input_;
  std::atomic<std::uint64_t> input_dropped_{0};  // the control thread writes, the trace thread reads
  const std::atomic<std::uint64_t>* output_dropped_ = nullptr;  // the step output's counter
  std::unique_ptr<gpio::TraceWriter> writer_;  // after the rings: stopped before they go
  bool loss_logged_ = false;
};

}  // namespace stepmod::tools

#pragma once
// The pulse thread's work, separated from the thread itself so that tests can run it in virtual
// time: take the earliest due edge over all axes, write it, account for it. Nothing here
// allocates, locks, logs or makes a system call other than the backend's line write.
#include <atomic>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "core/spsc_ring.hpp"
#include "core/trace_record.hpp"
#include "gpio/backend.hpp"
#include "rt/axis_feedback.hpp"
#include "rt/edge.hpp"
#include "rt/lateness_stats.hpp"

namespace stepmod::rt {

inline constexpr Nanos kNever = std::numeric_limits<Nanos>::max();

// Everything the pulse thread touches for one axis.
struct AxisLink {
  SpscRing<Edge>* edges = nullptr;   // consumer side: planner -> pulse thread
  AxisFeedback* feedback = nullptr;  // written here
  AxisControl* control = nullptr;    // read here (immediate stop)
  StepHistory* history = nullptr;    // written here
};

class PulseEngine {
 public:
  // `trace` may be null (no --trace). All links must outlive the engine.
  PulseEngine(gpio::Backend& backend, std::span<const AxisLink> axes, SpscRing<TraceRecord>* trace);

  // Applies pending immediate stops (drops the aborted motions' edges, brings a high step line
  // low, publishes the stop) and returns the time of the earliest pending edge, or kNever.
  Nanos next_due() noexcept;

  // Executes the earliest pending edge (next_due() must have returned a time), stamping the
  // write, the feedback and the trace with `write_time`; lateness = write_time - edge time.
  void execute_one(Nanos write_time) noexcept;

  // As of the last next_due(): some axis is in a motion (its last executed motion edge was not
  // the motion's last) and has no edge queued: the planner is behind, an edge may come any time.
  bool starved() const noexcept { return starved_; }
  // As of the last next_due(): the earliest time at which an axis whose ring is empty in the
  // middle of a motion may get its next edge (AxisControl::refill_at); kNever if no such axis.
  // Until then (less the spin) its empty ring is by plan: starved() may poll from then on.
  Nanos dry_until() const noexcept { return dry_until_; }

  LatenessStats& stats() noexcept { return stats_; }
  const LatenessStats& stats() const noexcept { return stats_; }
  // Any thread: trace records lost because the trace ring was full.
  std::uint64_t trace_dropped() const noexcept {
    return trace_dropped_.load(std::memory_order_relaxed);
  }
  // The same counter, for the trace thread to watch (gpio::TraceWriter::watch_losses).
  const std::atomic<std::uint64_t>& trace_dropped_counter() const noexcept {
    return trace_dropped_;
  }

  // Late-edge guard (issue 12): a motion edge whose write would come more than `limit` after
  // the time it is due (PulseEngine::due) is a fault of its axis, never a burst of catch-up
  // steps: the edge is not written, the rest of its motion is dropped (a step pulse under way
  // has already been completed: trailing edges are never cut), and the fault is published in
  // AxisFeedback. Within the limit, late edges are written (catching up). 0 = off (default:
  // the engine alone measures; stepmodd sets [rt] late_limit_us). Set before use.
  void set_late_limit(Nanos limit) noexcept { late_limit_ = limit > 0 ? limit : kNever; }
  Nanos late_limit() const noexcept { return late_limit_ == kNever ? 0 : late_limit_; }

  // The clock an immediate stop stamps its line write with (next_due() has no time argument).
  // Default monotonic_now; tests running in virtual time substitute theirs. Set before use.
  using ClockFn = Nanos (*)() noexcept;
  void set_clock(ClockFn clock) noexcept { clock_ = clock; }

 private:
  void apply_abort(unsigned axis) noexcept;
  void write(unsigned axis, OutputLine line, bool level, Nanos t) noexcept;
  void drop_stale(unsigned axis) noexcept;
  void drop_beyond_limit(unsigned axis) noexcept;
  // The late-edge guard's cut: drops motion `e.epoch` of `axis` and publishes the fault.
  void late_fault(unsigned axis, const Edge& e, Nanos late) noexcept;
  // When the head edge of `axis` may be written: its time, pushed back so that a late leading
  // edge still gets its full pulse width and a late direction edge its full set-up time.
  Nanos due(unsigned axis, const Edge& e) const noexcept;

  gpio::Backend& backend_;
  std::vector<AxisLink> axes_;  // sized once in the constructor
  std::vector<std::uint32_t> abort_seen_;
  SpscRing<TraceRecord>* trace_;
  LatenessStats stats_;
  int next_axis_ = -1;  // axis of the edge next_due() found
  bool starved_ = false;
  Nanos dry_until_ = kNever;
  std::atomic<std::uint64_t> trace_dropped_{0};
  // Per axis: the line of a step pulse whose leading edge was written and whose trailing edge
  // was not yet (kNoPulse if none): the line an immediate stop must bring low.
  static constexpr std::uint8_t kNoPulse = 0xff;
  std::vector<std::uint8_t> pulse_high_;
  std::vector<std::uint8_t> in_motion_;  // per axis: a motion's edges executed, not its last
  // Per axis: how late the leading edge of the pulse now high was written, and how late the last
  // direction edge was (until the next step): the trailing edge / next step keep their spacing.
  std::vector<Nanos> pulse_late_;
  std::vector<Nanos> dir_late_;
  std::vector<std::uint32_t> truncated_epoch_;  // per axis: motion cut at its step-count cap
  ClockFn clock_ = &monotonic_now;
  Nanos late_limit_ = kNever;
};

}  // namespace stepmod::rt

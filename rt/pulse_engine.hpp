#pragma once
// The pulse thread's work, separated from the thread itself so that tests can run it in virtual
// time: take the earliest due edge over all axes, write it, account for it. Nothing here
// allocates, locks, logs or makes a system call other than the backend's line write.
// It is the first step output's work (rt/step_output.hpp; rt/pulse_thread_output.hpp wires it to
// its thread); the control side reaches it only through that interface.
#include <atomic>
#include <cstdint>
#include <span>
#include <vector>

#include "core/spsc_ring.hpp"
#include "core/trace_record.hpp"
#include "gpio/backend.hpp"
#include "rt/axis_feedback.hpp"
#include "rt/edge.hpp"
#include "rt/lateness_stats.hpp"

namespace stepmod::rt {

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

  // Between next_due() and the clock read that stamps execute_one(): if the edge found is a
  // step, its axis' history is told a step is being stamped (StepHistory::announce), so that
  // no reader misses it. execute_one() ends that; withdraw() ends it when the edge is not due.
  void announce() noexcept;
  void withdraw() noexcept;

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

  // Late-edge guard (issue 18, the contract's "Late edges"). A late edge never starts a burst:
  // its motion's group slips (rt/slip.hpp). A step is a fault of its axis (and of the axes of
  // its group) when its pause — how much longer the gap since the axis' previous step is than
  // planned; for a motion's first step, how late it is — exceeds `limit` (any speed), or, above
  // the motion's starting speed Vs, when its lag — pause / planned interval, the whole steps that
  // were due during the pause — exceeds the axis' lag limit. The step is not written, the rest of
  // the motion is dropped (a step pulse under way has already been completed: trailing edges are
  // never cut), and the fault is published in AxisFeedback. 0 = off (default: the engine alone
  // slips and measures; stepmodd sets [rt] late_limit_us and [axis] lag_limit_steps). Set before
  // use.
  void set_late_limit(Nanos limit) noexcept { late_limit_ = limit > 0 ? limit : 0; }
  Nanos late_limit() const noexcept { return late_limit_; }
  void set_lag_limit(unsigned axis, std::uint32_t steps) noexcept {
    if (axis < track_.size()) track_[axis].lag_limit = steps;
  }
  // The slip of `axis`' motion now (tests, diagnostics); AxisFeedback::slip publishes it.
  Nanos slip(unsigned axis) const noexcept { return slip_of(axis); }

  // The clock an immediate stop stamps its line write with (next_due() has no time argument).
  // Default monotonic_now; tests running in virtual time substitute theirs. Set before use.
  using ClockFn = Nanos (*)() noexcept;
  void set_clock(ClockFn clock) noexcept { clock_ = clock; }

 private:
  // A guard's verdict on one motion edge (see set_late_limit).
  struct Verdict {
    Nanos pause = 0;
    std::int64_t lag = 0;  // steps (0 when not above Vs)
    Nanos interval = 0;    // planned interval from the previous step (0: first step, not a step)
    bool fault = false;
  };

  // Applies what was asked of `axis` since the last look (immediate stop, cut, step cap), binds
  // the motion of a head edge not yet bound, and returns the head edge (null: empty ring);
  // `refill_at`: the planner's promise for its next edge (AxisControl::refill_at). `unsettled`:
  // null because edges kept arriving while the checks ran (look again at once).
  const Edge* prepare_head(unsigned axis, Nanos& refill_at, bool& unsettled) noexcept;
  // One pass of the checks; true if every check looked at the head `e` it returns.
  bool examine_head(unsigned axis, Nanos& refill_at, const Edge*& e) noexcept;
  static constexpr int kHeadPasses = 4;  // prepare_head: passes of examine_head at most
  // Within a group, edges go out in planned-time order across the members: a member's edge
  // planned after the promised next edge of a starved member (its ring ran dry mid-motion: the
  // planner, held off, refills the members one after the other) waits until that edge has come;
  // then it goes out first, and its lateness slips the whole group (judged by the guard). Else
  // the member refilled first would run ahead of the other and the path would come apart.
  bool waits_for_group(unsigned axis, const Edge& e) const noexcept;
  void apply_abort(unsigned axis) noexcept;
  void execute_head(Nanos write_time) noexcept;  // execute_one() but the announcement's end
  void record_step(unsigned axis, const Edge& e, Nanos write_time, Nanos rest) noexcept;
  void publish_motion(unsigned axis, const Edge& e) noexcept;
  void write(unsigned axis, OutputLine line, bool level, Nanos t) noexcept;
  void drop_stale(unsigned axis) noexcept;
  void drop_beyond_limit(unsigned axis) noexcept;
  // Binds the motion of `e` (its first edge to reach the head) to a slip cell: its group's, or a
  // free one, with the slip it inherits (rt/slip.hpp kChainGapNs).
  void bind(unsigned axis, const Edge& e) noexcept;
  int find_cell(unsigned axis, std::uint32_t key) const noexcept;
  Nanos slip_of(unsigned axis) const noexcept {
    const std::uint8_t c = track_[axis].cell;
    return c == kNoCell ? 0 : cells_[c].slip;
  }
  // Publishes the slip of `cell` to the feedback of every axis bound to it.
  void publish_slip(std::uint8_t cell) noexcept;
  // After writing motion edge `e` at `write_time`: the lateness beyond kSlipFreeNs joins the
  // slip; returns the rest (<= kSlipFreeNs), which the next edge's due() keeps as spacing.
  Nanos absorb(unsigned axis, const Edge& e, Nanos write_time) noexcept;
  Verdict judge(unsigned axis, const Edge& e, Nanos write_time) const noexcept;
  // The guard's cut: drops `axis`' motion and every unfinished motion of its group.
  void fault_group(unsigned axis, const Verdict& v) noexcept;
  void late_fault(unsigned axis, std::uint32_t epoch, const Verdict& v) noexcept;
  // When the head edge of `axis` may be written: its planned time plus its motion's slip, pushed
  // back so that a leading edge a little late (within kSlipFreeNs) still gets its full pulse
  // width and a direction edge its full set-up time.
  Nanos due(unsigned axis, const Edge& e) const noexcept;

  gpio::Backend& backend_;
  std::vector<AxisLink> axes_;  // sized once in the constructor
  std::vector<std::uint32_t> abort_seen_;
  SpscRing<TraceRecord>* trace_;
  LatenessStats stats_;
  int next_axis_ = -1;                // axis of the edge next_due() found
  StepHistory* announced_ = nullptr;  // the history announce() told of a step, until it ends
  bool starved_ = false;
  Nanos dry_until_ = kNever;
  std::atomic<std::uint64_t> trace_dropped_{0};
  // Per axis: the line of a step pulse whose leading edge was written and whose trailing edge
  // was not yet (kNoPulse if none): the line an immediate stop must bring low.
  static constexpr std::uint8_t kNoPulse = 0xff;
  std::vector<std::uint8_t> pulse_high_;
  std::vector<std::uint8_t> in_motion_;  // per axis: a motion's edges executed, not its last
  // Per axis: how late (within kSlipFreeNs, beyond the slip) the leading edge of the pulse now
  // high was written, and the last direction edge (until the next step): the trailing edge /
  // next step keep their spacing.
  std::vector<Nanos> pulse_late_;
  std::vector<Nanos> dir_late_;
  std::vector<std::uint32_t> truncated_epoch_;  // per axis: motion cut at its step-count cap
  std::vector<const Edge*> heads_;  // per axis, as of next_due(): its ring's head (null: empty)

  // Slip cells: one per motion group running (a motion alone is a group of one). No more cells
  // than axes, so an axis that binds a new motion always finds a free one.
  static constexpr std::uint8_t kNoCell = 0xff;
  struct Cell {
    Nanos slip = 0;
    std::uint32_t key = 0;  // the group id (0: a motion alone, never joined)
    // As of next_due(): the earliest promised next edge (planned time) of a member whose ring
    // ran dry mid-motion; the members' edges planned after it wait (waits_for_group).
    Nanos wait_after = kNever;
  };
  std::vector<Cell> cells_;
  struct Track {  // per axis: its motion's binding and the guard's memory of its last step
    std::uint8_t cell = kNoCell;
    std::uint32_t epoch = 0;      // the motion bound (0: none yet)
    Nanos vs_interval = 0;        // its step interval at Vs (0: unknown: every step is above Vs)
    std::uint32_t lag_limit = 0;  // [axis] lag_limit_steps (0: off)
    bool have_last = false;       // a motion edge of this axis was written: the two below
    Nanos last_planned = 0;       // its planned time
    Nanos last_slip = 0;          // the slip it was written with
    bool step_seen = false;       // a step of the bound motion was written: the two below
    Nanos step_planned = 0;
    Nanos step_wire = 0;
  };
  std::vector<Track> track_;
  ClockFn clock_ = &monotonic_now;
  Nanos late_limit_ = 0;  // 0: off, as lag_limit
};

}  // namespace stepmod::rt

#pragma once
// State shared between the pulse thread and the rest of the daemon, one block per axis.
// AxisFeedback is written only by the pulse thread. AxisControl has two writers, one per field,
// never both: the module (control) thread writes the immediate-stop and step-cap fields
// (abort_epoch, limit_steps, limit_epoch); the planner thread writes what it tells the pulse
// thread about its own edges (refill_at, motion_group, motion_vs) and its side of `cut` (a
// request/answer handshake with the pulse thread, rt/edge_cut.hpp). Every field is a lone atomic:
// no locks on the real-time path.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <thread>

#include "core/clock.hpp"
#include "core/spsc_ring.hpp"
#include "rt/edge.hpp"
#include "rt/edge_cut.hpp"
#include "rt/slip.hpp"

namespace stepmod::rt {

struct AxisFeedback {
  std::atomic<std::int64_t> steps{0};   // net steps output since start, + = CW
  std::atomic<std::uint32_t> epoch{0};  // epoch of the last executed motion edge
  std::atomic<std::uint32_t> finished_epoch{
      0};                              // newest epoch that ended (kLast executed or aborted)
  std::atomic<std::uint8_t> flags{0};  // edge_flag bits of the last executed motion edge
  std::atomic<std::uint8_t> output_levels{0};  // bit per OutputLine: what the lines are driven to
  std::atomic<Nanos> last_step_t{0};           // time of the last step's leading edge
  // The slip of the axis' motion (rt/slip.hpp): pack_epoch(motion epoch, slip in us). Wire time
  // of a planned time t of that motion = t + slip. Updated whenever it grows.
  std::atomic<std::uint64_t> slip{0};
  // Planned interval between the axis' last two steps of one motion (0: its first step).
  std::atomic<Nanos> step_interval_ns{0};

  // Late-edge guard (PulseEngine::set_late_limit, set_lag_limit): a step whose pause (the gap
  // in the step train beyond the planned interval) is longer than the late limit, or, above the
  // starting speed, whose lag (steps due during the pause) exceeds the lag limit, is not
  // written; the rest of its motion (its group's) is dropped (as by an immediate stop) and the
  // fault is published here. Written in this order: the details, then
  // late_faults (release), then finished_epoch: a reader that sees the motion finished and
  // late_faults changed (acquire) sees the details of that fault. Two faults within one reader
  // pass may mix their details; the count never misses one.
  std::atomic<std::int64_t> fault_step{0};    // step count when the motion was cut
  std::atomic<Nanos> fault_late_ns{0};        // the pause at the dropped edge
  std::atomic<std::int64_t> fault_lag{0};     // its lag, in steps (0 below Vs: not judged)
  std::atomic<Nanos> fault_interval_ns{0};    // the planned step interval there (0: at rest)
  std::atomic<std::uint32_t> fault_epoch{0};  // the motion that was cut
  std::atomic<std::uint32_t> late_faults{0};  // faults since start
  std::atomic<Nanos> worst_fault_late_ns{0};  // the largest fault_late_ns so far
};

struct AxisControl {
  // --- Written by the module (control) thread ---
  // Immediate stop: motion edges whose epoch <= abort_epoch are dropped by the pulse thread, which
  // then brings a high step line low and reports the epoch in AxisFeedback::finished_epoch.
  std::atomic<std::uint32_t> abort_epoch{0};
  // Step-count cap (registration): motion `limit_epoch` may not take the step count past
  // `limit_steps` (beyond it in its own direction); the pulse thread drops its later steps. The
  // planner plans the stop from its frontier, a few ms ahead, so for a short count it may have
  // queued steps beyond it already: this makes the count exact anyway. Written limit_steps first
  // (relaxed), then limit_epoch (release).
  std::atomic<std::int64_t> limit_steps{0};
  std::atomic<std::uint32_t> limit_epoch{0};
  // --- Written by the planner thread (and, for `cut`, answered by the pulse thread) ---
  // Controlled stop at its trigger: between the planner thread and the pulse thread (not the
  // module): replaces a motion's queued edges from a time on (rt/edge_cut.hpp).
  EdgeCut cut;
  // Planner -> pulse thread: the planner's next edge for this axis (pushed by a refill, not by a
  // command) lies at or after this time (0: any time). While the axis' ring is empty in the
  // middle of a motion, the pulse thread need not poll for that edge before then: a path axis
  // waits for its next crossing with an empty ring by design (planner/path_source.hpp), and the
  // 50 us poll of a starved ring cost a one-CPU VM its whole CPU (a circle's edges 170 ms late).
  // Stored (release) after the edges pushed before it; read (acquire) before the ring is peeked.
  // Edges a command causes sooner come with the doorbell (PulseThread::ring).
  std::atomic<std::int64_t> refill_at{0};
  // Planner -> pulse thread, stored before a motion's first edge is pushed (rt/slip.hpp):
  // pack_epoch(epoch, group id; 0 = alone) and pack_epoch(epoch, vs_interval_ns(Vs)).
  std::atomic<std::uint64_t> motion_group{0};
  std::atomic<std::uint64_t> motion_vs{0};
};

// Time -> step count, for events stamped in the past (capture input, registration trigger).
// The pulse thread appends (t, steps) at each step's leading edge; readers search backwards.
class StepHistory {
 public:
  static constexpr std::size_t kSize = 4096;  // at 1 MHz: 4 ms of history

  // Pulse thread only, after each step's leading edge, with the count after that step. Every
  // step must be recorded, and the count starts at 0 (AxisFeedback::steps), so that the count
  // before the first recorded step is known to be 0.
  void record(Nanos t, std::int64_t steps) noexcept {
    const std::uint64_t i = count_.load(std::memory_order_relaxed);
    // Seqlock: announce the slot being overwritten before touching it. The entry's stores are
    // releases (free on x86), so a reader whose acquire load saw any part of the new entry also
    // sees `writing_` >= i + 1. (No fences: GCC's ThreadSanitizer does not support them.)
    writing_.store(i + 1, std::memory_order_relaxed);
    Entry& e = entries_[i % kSize];
    e.t.store(t, std::memory_order_release);
    e.steps.store(steps, std::memory_order_release);
    count_.store(i + 1, std::memory_order_release);
    stamping_.store((stamping_.load(std::memory_order_relaxed) | 1) + 1, std::memory_order_release);
  }

  // Pulse thread, before it reads the clock a step will be stamped with: until record() (or
  // withdraw(), no step after all) readers wait. Otherwise a reader asking about an event
  // stamped after that clock read, while the pulse thread is between the read and the record,
  // would miss the step (a registration or capture one step short). Sequentially consistent: the
  // store is visible before the clock read that follows it (the vDSO's counter read is ordered).
  void announce() noexcept {
    stamping_.store(stamping_.load(std::memory_order_relaxed) | 1, std::memory_order_seq_cst);
  }
  void withdraw() noexcept {
    stamping_.store((stamping_.load(std::memory_order_relaxed) | 1) + 1, std::memory_order_release);
  }
  // A step announced and not yet recorded or withdrawn (tests).
  bool stamping() const noexcept { return (stamping_.load(std::memory_order_acquire) & 1) != 0; }

  // Step count at time t: the count after the last step at or before t (0 if t is before the
  // first step ever). `now_steps` is returned when no step has been recorded yet. Returns false
  // if t is older than the history still held, or if the writer kept overwriting the entries
  // being read (only if the reader is preempted for most of kSize steps).
  bool steps_at(Nanos t, std::int64_t now_steps, std::int64_t& out) const noexcept {
    wait_for_stamp();
    for (int attempt = 0; attempt < 4; ++attempt) {
      const std::uint64_t n = count_.load(std::memory_order_acquire);
      if (n == 0) {
        out = now_steps;
        return true;
      }
      // Entries [n - kSize, n) are intact now; leave the writer kMargin entries of room to
      // write while we read before the oldest one we look at is overwritten.
      const std::uint64_t lowest = n > kSize - kMargin ? n - (kSize - kMargin) : 0;
      std::uint64_t i = n;
      std::int64_t result = 0;
      bool found = false;
      while (i > lowest) {
        --i;
        const Entry& e = entries_[i % kSize];
        if (e.t.load(std::memory_order_acquire) <= t) {
          result = e.steps.load(std::memory_order_acquire);
          found = true;
          break;
        }
      }
      // Walked past the very first step without finding one at or before t: t precedes it.
      if (!found && i == 0) found = true;  // result stays 0
      // Writes of indices < w overwrote indices < w - kSize; all we read is index >= i.
      const std::uint64_t w = writing_.load(std::memory_order_relaxed);
      if (w <= i + kSize) {
        if (found) out = result;
        return found;
      }
    }
    return false;
  }

 private:
  static constexpr std::size_t kMargin = 64;
  // Readers: until no step is between its clock read and its record (announce()). The pulse
  // thread is there for well under a microsecond unless preempted (not real-time, or a loaded
  // test machine): then yield to it, for at most kStampWait; after that, answer as things are.
  static constexpr Nanos kStampWait = 10 * kNsPerMs;
  void wait_for_stamp() const noexcept {
    if ((stamping_.load(std::memory_order_acquire) & 1) == 0) return;
    const Nanos give_up = monotonic_now() + kStampWait;
    for (int spins = 0; (stamping_.load(std::memory_order_acquire) & 1) != 0; ++spins) {
      if (spins < 100) continue;
      if (monotonic_now() > give_up) return;
      std::this_thread::yield();
    }
  }
  struct Entry {
    std::atomic<Nanos> t{0};
    std::atomic<std::int64_t> steps{0};
  };
  Entry entries_[kSize];
  std::atomic<std::uint64_t> count_{0};     // entries completely written
  std::atomic<std::uint64_t> writing_{0};   // entries whose writing has begun
  std::atomic<std::uint64_t> stamping_{0};  // odd: a step is being stamped (announce())
};

// Everything a step output (rt/step_output.hpp) touches for one axis.
struct AxisLink {
  SpscRing<Edge>* edges = nullptr;   // consumer side: planner -> step output
  AxisFeedback* feedback = nullptr;  // written by the step output
  AxisControl* control = nullptr;    // read by it (immediate stop, cap, cut; written: cut's answer)
  StepHistory* history = nullptr;    // written by it
};

}  // namespace stepmod::rt

#pragma once
// State shared between the pulse thread and the rest of the daemon, one block per axis.
// AxisFeedback is written only by the pulse thread; AxisControl only by the module (control)
// thread. Every field is a lone atomic: no locks on the real-time path.
#include <atomic>
#include <cstdint>

#include "rt/clock.hpp"
#include "rt/edge.hpp"

namespace stepmod::rt {

struct AxisFeedback {
  std::atomic<std::int64_t> steps{0};          // net steps output since start, + = CW
  std::atomic<std::uint32_t> epoch{0};         // epoch of the last executed motion edge
  std::atomic<std::uint32_t> finished_epoch{0};// newest epoch that ended (kLast executed or aborted)
  std::atomic<std::uint8_t> flags{0};          // edge_flag bits of the last executed motion edge
  std::atomic<std::uint8_t> output_levels{0};  // bit per OutputLine: what the lines are driven to
  std::atomic<Nanos> last_step_t{0};           // time of the last step's leading edge
};

struct AxisControl {
  // Immediate stop: motion edges whose epoch <= abort_epoch are dropped by the pulse thread, which
  // then brings a high step line low and reports the epoch in AxisFeedback::finished_epoch.
  std::atomic<std::uint32_t> abort_epoch{0};
};

// Time -> step count, for events stamped in the past (capture input, registration trigger).
// The pulse thread appends (t, steps) at each step's leading edge; readers search backwards.
class StepHistory {
 public:
  static constexpr std::size_t kSize = 4096;  // at 1 MHz: 4 ms of history

  void record(Nanos t, std::int64_t steps) noexcept {
    const std::uint64_t i = count_.load(std::memory_order_relaxed);
    Entry& e = entries_[i % kSize];
    e.t.store(t, std::memory_order_relaxed);
    e.steps.store(steps, std::memory_order_relaxed);
    count_.store(i + 1, std::memory_order_release);
  }

  // Step count at time t: the count after the last step at or before t. `now_steps` is returned
  // when no recorded step is newer than t. Returns false if t is older than the history.
  bool steps_at(Nanos t, std::int64_t now_steps, std::int64_t& out) const noexcept {
    for (int attempt = 0; attempt < 4; ++attempt) {
      const std::uint64_t n = count_.load(std::memory_order_acquire);
      std::int64_t result = now_steps;
      bool found = n == 0;
      const std::uint64_t oldest = n > kSize ? n - kSize + 64 : 0;  // margin against the writer
      for (std::uint64_t i = n; i > oldest; --i) {
        const Entry& e = entries_[(i - 1) % kSize];
        const Nanos et = e.t.load(std::memory_order_relaxed);
        if (et <= t) {
          result = e.steps.load(std::memory_order_relaxed);
          found = true;
          break;
        }
        // A step after t: before it the count was one step back toward this step's predecessor.
        result = (i >= 2) ? entries_[(i - 2) % kSize].steps.load(std::memory_order_relaxed) : 0;
        found = (i - 1 == 0);
      }
      std::atomic_thread_fence(std::memory_order_acquire);
      if (count_.load(std::memory_order_relaxed) - n < kSize - 64) {
        if (found) out = result;
        return found;
      }
    }
    return false;
  }

 private:
  struct Entry {
    std::atomic<Nanos> t{0};
    std::atomic<std::int64_t> steps{0};
  };
  Entry entries_[kSize];
  std::atomic<std::uint64_t> count_{0};
};

}  // namespace stepmod::rt

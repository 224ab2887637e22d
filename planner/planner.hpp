#pragma once
// The planner: turns Commands into edge schedules, a few milliseconds ahead of the pulse thread.
// It owns the producer side of every axis' edge ring. `service()` is the whole job; the planner
// thread (planner_thread.hpp) only calls it and sleeps, so tests can run it in virtual time.
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/spsc_ring.hpp"
#include "planner/motion_port.hpp"
#include "planner/motion_request.hpp"
#include "planner/path_book.hpp"
#include "rt/axis_feedback.hpp"
#include "rt/edge.hpp"

namespace stepmod::planner {

struct AxisTiming {
  Nanos step_pulse_ns = 2'000;  // width of a step pulse (shortened to half the period if needed)
  Nanos dir_setup_ns = 5'000;   // direction change -> next step edge
};

struct PlannerAxis {
  SpscRing<rt::Edge>* edges = nullptr;  // producer side
  rt::AxisControl* control = nullptr;   // abort_epoch: skip aborted motions; cut (stops)
  AxisTiming timing;
  // The pulse thread's slip of the axis' motion (rt/slip.hpp); null: none (no slip is seen).
  const rt::AxisFeedback* feedback = nullptr;
};

struct PlannerOptions {
  Nanos lookahead_ns = 4 * kNsPerMs;      // keep each ring filled this far ahead of `now`
  Nanos start_delay_ns = 150 * kNsPerUs;  // a new motion's time 0 is at least this after `now`
  std::size_t command_queue = 64;
  // A stop with a trigger time replaces queued edges from max(trigger, now + this) on: time for
  // the pulse thread to see the cut before it runs the first edge it drops (rt/edge_cut.hpp).
  Nanos cut_margin_ns = 100 * kNsPerUs;
  // A rack (docs/ARCHITECTURE.md, "A rack"): each module has a planner of its own, and one
  // planner thread serves them all. The planners then share one wake counter (the thread sleeps
  // on it; null: the planner's own), and each puts its module's number in the top 8 bits of the
  // group keys the pulse thread sees, so that two modules' groups never share a slip cell or a
  // late-edge fault.
  std::atomic<std::uint32_t>* wake_counter = nullptr;
  std::uint8_t group_domain = 0;
};

class AxisPlanner;  // planner/axis_planner.hpp

class Planner final : public CommandSink {
 public:
  Planner(std::span<const PlannerAxis> axes, PlannerOptions options = {});
  ~Planner() override;

  // Control thread (single producer).
  bool submit(const Command& c) noexcept override;
  bool submit_blend(Command c, const BlendSpec& b) noexcept override;

  // Planner thread: applies the queued commands and fills every ring up to now + lookahead.
  // Returns the time at which it should run again at the latest.
  Nanos service(Nanos now);

  // For the planner thread's sleep: a counter bumped by submit(), so a sleeper can be woken.
  std::atomic<std::uint32_t>& wake_counter() noexcept { return *wake_; }
  // The wake counter as read at the start of the last service() that left nothing submitted
  // before it unplanned (no group start still collecting its members): equal to the wake
  // counter, every command submitted so far is in the edge rings. The step output's doorbell
  // rings again then (planner/output_doorbell.hpp).
  std::uint32_t served() const noexcept { return served_.load(std::memory_order_acquire); }
  std::uint32_t wakes() const noexcept { return wake_->load(std::memory_order_acquire); }
  const PlannerOptions& options() const noexcept { return options_; }

 private:
  // A blend's segment table on its way from the control thread to the planner thread. The
  // control thread writes `spec` only while the planner has taken every blend handed over before
  // (taken == handed), then submits the BlendStart command: the command ring's release/acquire
  // orders the write before the planner's read, and `taken` (release, after the planner's copy)
  // orders that read before the next write.
  struct BlendSlot {
    BlendSpec spec;
    std::uint32_t handed = 0;  // control thread only: the newest seq submitted
    std::atomic<std::uint32_t> taken{0};
  };
  void apply(const Command& c, Nanos now);
  // Starts the group being collected (all of its members that arrived) on one time 0.
  void launch_group(Nanos now);

  PlannerOptions options_;
  std::vector<std::unique_ptr<AxisPlanner>> axes_;
  std::unique_ptr<BlendSlot[]> blend_slots_;
  SpscRing<Command> queue_;
  std::atomic<std::uint32_t> own_wake_{0};
  std::atomic<std::uint32_t>* wake_ = options_.wake_counter ? options_.wake_counter : &own_wake_;
  std::atomic<std::uint32_t> served_{0};
  // The group start being collected: its id, size, the commands received, and the axes that
  // accepted theirs (an aborted or stale start is not a member any more).
  GroupTag group_{};
  std::size_t group_received_ = 0;
  Nanos group_deadline_ = 0;
  std::vector<unsigned> group_axes_;
  // The last group launched without all its members (the start delay ran out first): a member
  // that arrives after all joins its time 0 (see apply()).
  struct Launched {
    std::uint32_t id = 0;
    std::size_t missing = 0;
    Nanos origin = 0;
  };
  Launched launched_;
  std::vector<Nanos> fill_slip_;  // service(): each axis' slip for this fill (see there)
  PathBook paths_{axes_, options_.start_delay_ns};  // the interpolated paths across the axes
};

}  // namespace stepmod::planner

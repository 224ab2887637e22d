#pragma once
// The daemon's stack (tools::Stack) on the simulated machine, run in virtual time in one
// thread: the planner is serviced, edges are executed at their own times, input events reach the
// personality right after the edge that caused them, and the PLC image is scanned every scan
// period. Deterministic and fast: a 2-second homing pause costs nothing.
#include <functional>
#include <memory>
#include <vector>

#include "daemon/stack.hpp"
#include "gpio/sim_backend.hpp"
#include "module/personality.hpp"

namespace stepmod::testing {

struct VirtualMachineOptions {
  ModuleType type = ModuleType::k3601;
  std::vector<gpio::SimAxisSetup> axes;  // one per axis of the module
  Nanos scan_ns = kNsPerMs;
  planner::AxisTiming timing;
  // The late-edge guard, at stepmodd's defaults ([rt] late_limit_us, [axis] lag_limit_steps).
  Nanos late_limit_ns = 200 * kNsPerMs;
  std::uint32_t lag_limit_steps = 8;
};

// A typical machine for one 3601 axis: every input wired, limits at +-100,000, home 5,000..5,100.
VirtualMachineOptions default_3601();

class VirtualMachine {
 public:
  explicit VirtualMachine(VirtualMachineOptions options);

  ModuleType type() const noexcept { return options_.type; }
  Nanos now() const noexcept { return now_; }
  // Runs every event up to and including `t`.
  void run_until(Nanos t);
  void run_for(Nanos d) { run_until(now_ + d); }
  void scans(unsigned n) { run_for(static_cast<Nanos>(n) * options_.scan_ns); }
  // Runs until `done()` holds after a scan, at most `limit`; returns whether it held.
  bool run_until_true(const std::function<bool()>& done, Nanos limit);

  ImageWords& plc_out() noexcept { return plc_out_; }
  const ImageWords& plc_in() const noexcept { return plc_in_; }
  gpio::SimBackend& sim() noexcept { return *sim_; }
  // The module's own stack (the machine is a rack of one).
  tools::ModuleStack& stack() noexcept { return stack_->module(0); }

  // From `from` on, for `length`, the pulse thread is stalled (a vCPU stolen, SIGSTOP): edges due
  // in that window are executed when it ends, late (the late-edge guard's test).
  void stall_pulse_thread(Nanos from, Nanos length) {
    stall_from_ = from;
    stall_to_ = from + length;
  }

  // Test seam (A32, 3602-IP-03): sets `axis`' net step count, the pulse thread's feedback that
  // the position is reckoned from, as if that many steps had been output. Positions near 2^31
  // take ~10^9 steps to reach (18 min at 1 MHz even in virtual time's edge-by-edge run); this
  // puts the axis there at rest. The step history (capture, registration) does not follow: use
  // it with the axis idle and for commands that need no capture. The daemon has no such call.
  void set_step_count(unsigned axis, std::int64_t steps) {
    // The feedback is the stack's own (non-const) object; only the pulse thread writes it, and
    // in virtual time the pulse thread is this thread.
    const_cast<rt::AxisFeedback&>(stack_->module(0).feedback(axis)).steps.store(steps);
  }

  // Step (leading) edges written so far, per axis, and their times.
  const std::vector<Nanos>& step_times(unsigned axis) const { return step_times_[axis]; }

 private:
  void deliver_inputs();

  VirtualMachineOptions options_;
  std::unique_ptr<gpio::SimBackend> sim_;
  std::unique_ptr<tools::Stack> stack_;
  ImageWords plc_out_{};
  ImageWords plc_in_{};
  Nanos now_;
  Nanos next_scan_;
  Nanos next_plan_;
  std::uint32_t planner_wakes_ = 0;  // Planner::wake_counter() as of the last service
  std::vector<std::vector<Nanos>> step_times_;
  std::vector<std::int64_t> last_steps_;
  Nanos stall_from_ = 0;
  Nanos stall_to_ = 0;
};

}  // namespace stepmod::testing

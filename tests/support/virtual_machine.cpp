#include "tests/support/virtual_machine.hpp"

#include <algorithm>
#include <array>

namespace stepmod::testing {

namespace {
// Virtual time starts at 1 s so that every time is positive and "time 0" is never a real edge.
constexpr Nanos kStart = kNsPerSec;
// The daemon's planner thread wakes on a command within tens of microseconds; model that.
constexpr Nanos kPlannerWake = 20 * kNsPerUs;
// The planner is serviced at least this often even when it asks for less (bounded staleness).
constexpr Nanos kPlannerMaxSleep = kNsPerMs;

// The step output stamps the writes it makes on its own (an immediate stop ending a pulse) with
// its clock: in virtual time that is the machine's `now`. One machine runs at a time per thread.
thread_local Nanos t_virtual_now = kStart;
Nanos virtual_clock() noexcept {
  return t_virtual_now;
}
}  // namespace

VirtualMachineOptions default_3601() {
  VirtualMachineOptions o;
  gpio::SimAxisSetup a;
  unsigned offset = 0;
  for (auto& line : a.lines.out) line = offset++;
  for (auto& line : a.lines.in) line = offset++;
  a.lines.out[static_cast<unsigned>(OutputLine::kGpo)].reset();  // 3602 only
  a.sim.cw_limit_at = 100'000;
  a.sim.ccw_limit_at = -100'000;
  a.sim.home_from = 5'000;
  a.sim.home_to = 5'100;
  a.sim.encoder_ratio = 1.0;
  a.sim.marker_every = 4'000;
  o.axes.push_back(a);
  return o;
}

VirtualMachine::VirtualMachine(VirtualMachineOptions options)
    : options_(std::move(options)), now_(kStart), next_scan_(kStart), next_plan_(kStart) {
  sim_ = std::make_unique<gpio::SimBackend>(options_.axes);
  tools::StackOptions so;
  so.type = options_.type;
  so.timing.assign(options_.axes.size(), options_.timing);
  so.late_limit_ns = options_.late_limit_ns;
  so.lag_limit_steps.assign(options_.axes.size(), options_.lag_limit_steps);
  stack_ = std::make_unique<tools::Stack>(so, *sim_, nullptr);
  stack_->output().set_clock(&virtual_clock);
  step_times_.resize(options_.axes.size());
  last_steps_.assign(options_.axes.size(), 0);
}

void VirtualMachine::deliver_inputs() {
  std::array<gpio::InputEvent, 256> events{};
  for (;;) {
    // A deadline in the past: take what is there, never sleep.
    const std::size_t n = sim_->wait_events(events, 0);
    for (std::size_t i = 0; i < n; ++i) {
      stack_->module(0).personality().on_input(tools::to_module_event(events[i]));
    }
    if (n < events.size()) return;
  }
}

void VirtualMachine::run_until(Nanos t) {
  rt::StepOutput& output = stack_->output();
  for (;;) {
    Nanos edge = output.next_due();
    // A stalled pulse thread writes what fell due in the stall when the stall ends.
    if (edge != rt::kNever && edge >= stall_from_ && edge < stall_to_) edge = stall_to_;
    const Nanos next = std::min({edge, next_scan_, next_plan_});
    if (next > t) break;
    now_ = next;
    t_virtual_now = now_;
    if (edge == now_) {
      output.execute_one(now_);
      for (unsigned a = 0; a < last_steps_.size(); ++a) {
        const std::int64_t s = stack_->module(0).feedback(a).steps.load();
        if (s != last_steps_[a]) step_times_[a].push_back(now_);
        last_steps_[a] = s;
      }
      deliver_inputs();
      // An input handler that submitted a command wakes the planner, as in the daemon.
      if (stack_->module(0).planner().wake_counter().load() != planner_wakes_) {
        next_plan_ = std::min(next_plan_, now_ + kPlannerWake);
      }
    } else if (next_plan_ == now_) {
      planner_wakes_ = stack_->module(0).planner().wake_counter().load();
      const Nanos want = stack_->module(0).planner().service(now_);
      next_plan_ = std::clamp(want, now_ + 1, now_ + kPlannerMaxSleep);
    } else {
      deliver_inputs();
      stack_->module(0).personality().scan(plc_out_, plc_in_, now_);
      next_scan_ += options_.scan_ns;
      next_plan_ = std::min(next_plan_, now_ + kPlannerWake);  // a scan may have submitted
    }
  }
  now_ = std::max(now_, t);
  t_virtual_now = now_;
}

bool VirtualMachine::run_until_true(const std::function<bool()>& done, Nanos limit) {
  const Nanos end = now_ + limit;
  while (now_ < end) {
    run_until(std::min(next_scan_, end));
    if (done()) return true;
  }
  return done();
}

}  // namespace stepmod::testing

#include "tests/module/axis_rig.hpp"

#include <algorithm>
#include <array>

#include "tests/support/virtual_machine.hpp"

namespace stepmod::testing {

namespace {
constexpr Nanos kStart = kNsPerSec;  // every time positive, as in virtual_machine.cpp
constexpr Nanos kPlannerWake = 20 * kNsPerUs;
constexpr Nanos kPlannerMaxSleep = kNsPerMs;

thread_local Nanos t_rig_now = kStart;
Nanos rig_clock() noexcept {
  return t_rig_now;
}
}  // namespace

ax::AxisConfig full_axis_config() {
  ax::AxisConfig c;
  c.inputs_used = 0x3F;  // capture, external, home, E-stop, CW limit, CCW limit
  c.inputs_active_high = 0x3F;
  c.quadrature_encoder = true;
  c.step_dir_output = true;
  c.homing = ax::HomingVariant::kSwitch;
  c.starting_speed = 1'000;
  return c;
}

AxisRig::AxisRig(const ax::ModuleRules& rules)
    : now_(kStart), next_scan_(kStart), next_plan_(kStart) {
  // The machine of default_3601(): limits at +-100,000, home 5,000..5,100, encoder 1:1.
  const VirtualMachineOptions o = default_3601();
  sim_ = std::make_unique<gpio::SimBackend>(o.axes);
  tools::StackOptions so;
  so.type = ModuleType::k3601;  // the stack's one-axis shape; its own personality stays unused
  so.timing.assign(o.axes.size(), o.timing);
  stack_ = std::make_unique<tools::Stack>(so, *sim_, nullptr);
  stack_->output().set_clock(&rig_clock);
  t_rig_now = now_;
  io_ = std::make_unique<tools::BackendAxisIo>(*sim_);
  axis_ = std::make_unique<ax::Axis>(rules, *io_, stack_->module(0).motion(0));
  status_ = axis_->status();
}

AxisRig::~AxisRig() = default;

void AxisRig::configure(std::optional<ax::AxisConfig> cfg) {
  image_ = ax::AxisCommand{};
  image_.configuration_mode = true;
  config_words_ = cfg;
  scans(3);
  image_ = ax::AxisCommand{};
  scans(3);
}

void AxisRig::hold(ax::CommandKind k, const Params& p) {
  image_.commands = ax::CommandSet{};
  image_.commands.set(k);
  image_.target = p.target;
  image_.speed = p.speed;
  image_.accel = p.accel;
  image_.decel = p.decel;
}

void AxisRig::clear() {
  image_.commands = ax::CommandSet{};
}

void AxisRig::command(ax::CommandKind k, const Params& p) {
  hold(k, p);
  scans(3);
  clear();
  scans(1);
}

void AxisRig::force(InputLine l, bool level) {
  const std::uint32_t bit = 1u << static_cast<unsigned>(l);
  forced_mask_ |= bit;
  forced_levels_ = level ? (forced_levels_ | bit) : (forced_levels_ & ~bit);
  sim_->force(0, forced_mask_, forced_levels_, now_);
}

void AxisRig::deliver_inputs() {
  std::array<gpio::InputEvent, 256> events{};
  for (;;) {
    const std::size_t n = sim_->wait_events(events, 0);
    pending_inputs_.insert(pending_inputs_.end(), events.begin(), events.begin() + n);
    if (n < events.size()) break;
  }
  while (!pending_inputs_.empty() && pending_inputs_.front().t + input_delay_ <= now_) {
    axis_->on_input(tools::to_module_event(pending_inputs_.front()));
    pending_inputs_.pop_front();
  }
}

void AxisRig::step_until(Nanos t) {
  rt::StepOutput& output = stack_->output();
  for (;;) {
    const Nanos edge = output.next_due();
    const Nanos next = std::min({edge, next_scan_, next_plan_});
    if (next > t) break;
    now_ = next;
    t_rig_now = now_;
    if (edge == now_) {
      output.execute_one(now_);
      deliver_inputs();
    } else if (next_plan_ == now_) {
      const Nanos want = stack_->module(0).planner().service(now_);
      next_plan_ = std::clamp(want, now_ + 1, now_ + kPlannerMaxSleep);
    } else {
      deliver_inputs();
      axis_->scan(image_, config_words_, now_);
      next_scan_ += kScan;
      next_plan_ = std::min(next_plan_, now_ + kPlannerWake);
      // Edges and planning only: the next scan is after it (scan_to_status_ < kScan).
      if (scan_to_status_ > 0) step_until(now_ + scan_to_status_);
      status_ = axis_->status();
    }
  }
  now_ = std::max(now_, t);
  t_rig_now = now_;
}

void AxisRig::run_for(Nanos d) {
  step_until(now_ + d);
}

bool AxisRig::run_until_true(const std::function<bool()>& done, Nanos limit) {
  const Nanos end = now_ + limit;
  while (now_ < end) {
    step_until(std::min(next_scan_, end));
    if (done()) return true;
  }
  return done();
}

bool AxisRig::wait_idle(Nanos limit) {
  return run_until_true([this] { return !moving(); }, limit);
}

}  // namespace stepmod::testing

#pragma once
// The shared axis (module/axis/) alone on the real planner, step output and simulated machine,
// in virtual time, driven with decoded commands: what every module's dialect hands it. One test
// body runs for each module type's ModuleRules (3601, 3602, 3202), so the rules the manuals share
// are tested once and every module inherits them.
#include <gtest/gtest.h>

#include <deque>
#include <memory>
#include <optional>

#include "gpio/sim_backend.hpp"
#include "module/axis/axis.hpp"
#include "daemon/module_io.hpp"
#include "daemon/stack.hpp"

namespace stepmod::testing {

namespace ax = module::axis;

// A configuration every test can start from: home input, both limits, E-stop, External and
// capture used and active high, the quadrature encoder, step/direction outputs, Vs = 1,000.
ax::AxisConfig full_axis_config();

// A move's parameters, decoded: steps, steps/s, steps/s^2.
struct Params {
  std::int32_t target = 0;
  std::int32_t speed = 10'000;
  std::int64_t accel = 10'000;
  std::int64_t decel = 10'000;
};

class AxisRig {
 public:
  explicit AxisRig(const ax::ModuleRules& rules);
  ~AxisRig();

  // Configuration mode with `cfg` (nullopt: an invalid configuration) for a few scans, then
  // command mode with an empty command image.
  void configure(std::optional<ax::AxisConfig> cfg = full_axis_config());
  // The decoded command image the PLC holds; scans read it.
  ax::AxisCommand& image() noexcept { return image_; }
  // An edge-triggered command the way a PLC issues it: set for a few scans, then cleared.
  void command(ax::CommandKind k, const Params& p = {});
  // Sets the command image to `k` with `p` (held until changed).
  void hold(ax::CommandKind k, const Params& p = {});
  void clear();

  void scans(unsigned n) { run_for(static_cast<Nanos>(n) * kScan); }
  // The control thread held off the CPU for `d` (< kScan) between a scan and its status, while
  // the pulse thread and the planner go on: what a loaded machine does now and then.
  void preempt_between_scan_and_status(Nanos d) noexcept { scan_to_status_ = d; }
  // Input events reach the axis only `d` after their stamp (at the first scan or edge after):
  // the line-event path of a loaded machine, behind the pulse thread's own feedback.
  void delay_inputs(Nanos d) noexcept { input_delay_ = d; }
  void run_for(Nanos d);
  // Runs until the axis is at rest (no direction shown), at most `limit`.
  bool wait_idle(Nanos limit = 30 * kNsPerSec);
  bool run_until_true(const std::function<bool()>& done, Nanos limit);

  const ax::AxisStatus& status() const noexcept { return status_; }
  // The axis itself, for the calls that are no command image (the 3202's blend message).
  ax::Axis& axis() noexcept { return *axis_; }
  bool moving() const noexcept { return status_.moving_cw || status_.moving_ccw; }
  std::int64_t motor() { return sim_->position(0); }
  // Panel: force an input's electrical level.
  void force(InputLine l, bool level);

  static constexpr Nanos kScan = kNsPerMs;

 private:
  void step_until(Nanos t);
  void deliver_inputs();

  std::unique_ptr<gpio::SimBackend> sim_;
  std::unique_ptr<tools::Stack> stack_;
  std::unique_ptr<tools::BackendAxisIo> io_;  // the axis' view of sim_, as the daemon's
  std::unique_ptr<ax::Axis> axis_;
  ax::AxisCommand image_;
  std::optional<ax::AxisConfig> config_words_;  // what the image means as configuration words
  ax::AxisStatus status_;
  Nanos now_;
  Nanos next_scan_;
  Nanos next_plan_;
  Nanos scan_to_status_ = 0;
  Nanos input_delay_ = 0;
  std::deque<gpio::InputEvent> pending_inputs_;  // taken from the machine, not yet delivered
  std::uint32_t forced_mask_ = 0;
  std::uint32_t forced_levels_ = 0;
};

}  // namespace stepmod::testing

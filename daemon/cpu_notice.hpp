#pragma once
// The "needs a CPU of its own" notice (issue 12 item 5, issue 18; docs/slip.md): a motion whose
// edges come closer together than the pulse thread's early wake-up keeps that thread on its CPU
// for the whole move. On a CPU shared with other threads the kernel then takes it away now and
// then (RT throttling, the fair server: tens of ms): the schedule slips, and above Vs a pause
// of more than [axis] lag_limit_steps steps is a fault. Said once per motion, from the control
// thread (never the pulse thread).
#include <cstdint>
#include <vector>

#include "config/config.hpp"
#include "rt/step_output.hpp"

namespace stepmod::tools {

class ModuleStack;

class CpuNotice {
 public:
  CpuNotice(ModuleStack& stack, const Config& config, const rt::StepOutput& pulse);
  // Control thread, per scan.
  void scan();

 private:
  void warn(unsigned axis, Nanos interval) const;

  ModuleStack& stack_;
  const Config& config_;
  const rt::StepOutput& pulse_;
  std::vector<std::uint32_t> noticed_epoch_;  // per axis: the motion last noticed
};

}  // namespace stepmod::tools

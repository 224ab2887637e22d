#pragma once
// The daemon health words of the input image (docs/interface.md 3.3) for each scan: the PLC
// supervision's and the lease's flags, the late-edge faults (bit 0, count, worst lateness; each
// new fault logged), lost input events (bit 5) and lost trace records (bit 4). Control thread.
#include <cstdint>
#include <vector>

#include "config/config.hpp"
#include "ipc/shm_image.hpp"
#include "planner/motion_port.hpp"

namespace stepmod::tools {

class ModuleTrace;
class LostInputWatch;
class ModuleStack;

class HealthWords {
 public:
  // `trace` may be null (no --trace).
  HealthWords(ModuleStack& stack, const Config& config, const LostInputWatch& lost_inputs,
              ModuleTrace* trace);

  ipc::Health scan(std::uint32_t supervisor_flags);

  // A late-edge fault stands from the fault until the axis' next motion (the PLC's next accepted
  // command): health bit 0, and a drive-enable release condition.
  static bool late_fault_lasts(const planner::MotionPort& m) noexcept {
    const planner::MotionPort::LateFault f = m.late_fault();
    return f.count != 0 && f.epoch == m.epoch();
  }

 private:
  void log_fault(unsigned axis, const planner::MotionPort::LateFault& f) const;

  ModuleStack& stack_;
  const Config& config_;
  const LostInputWatch& lost_inputs_;
  ModuleTrace* trace_;
  std::vector<std::uint32_t> faults_seen_;  // per axis: faults already logged
};

}  // namespace stepmod::tools

#include "daemon/realtime_setup.hpp"

#include <spdlog/spdlog.h>

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <cstring>

#include "rt/limits_hint.hpp"

namespace stepmod::tools {

rt::StepOutput::Options pulse_options(const Config& config) {
  rt::StepOutput::Options po;
  po.priority = config.rt_priority;
  po.cpu = config.rt_cpu;
#ifdef STEPMOD_SANITIZED
  po.lock_memory = false;  // the sanitizers' shadow memory cannot be locked
#endif
  // Every command reaches the pulse thread through the doorbell (PulseDoorbell): between
  // commands it need not poll (issue 5: an idle daemon polling every 50 us used a fifth of a core).
  po.quiet_sleep_ns = 100 * kNsPerMs;
  return po;
}

void warn_pulse_setup(const rt::StepOutput::Options& po, const rt::StepOutput::Status& st) {
  if (!st.fifo) {
    spdlog::warn(
        "pulse thread: SCHED_FIFO priority {} refused ({}); running without real-time "
        "priority: pulse timing will suffer under load{}",
        po.priority, std::strerror(st.sched_errno), rt::rtprio_fix(st.sched_errno));
  }
  if (!po.lock_memory) {
    // A sanitizer build never asks (its shadow memory cannot be locked): no refusal to report.
    spdlog::info("memory locking is off in this sanitizer build");
  } else if (!st.memory_locked) {
    spdlog::warn("mlockall refused ({}); memory is not locked{}", std::strerror(st.mlock_errno),
                 rt::memlock_fix(st.mlock_errno));
  }
  if (po.cpu >= 0 && !st.pinned) {
    spdlog::warn("cannot pin the pulse thread to CPU {} ({})", po.cpu,
                 std::strerror(st.affinity_errno));
  }
}

// Real-time below the control thread (issue 18): under CPU hogs a normal-priority planner was
// held off for milliseconds, the pulse thread's 4 ms of edges ran dry and the steps paused.
void raise_planner_thread(planner::PlannerThread& planner, int rt_priority) {
  if (rt_priority <= 0) return;
  const int prio = std::max(1, rt_priority - 20);
  if (const int rc = planner.set_realtime(prio); rc != 0) {
    spdlog::warn("planner thread: SCHED_FIFO priority {} refused ({}): steps may pause under load",
                 prio, std::strerror(rc));
  }
}

// The control thread reads the input edges. The v1 GPIO uAPI keeps only 16 unread edges per
// line and drops further ones silently, so this thread must run as soon as an edge arrives,
// not when the scheduler next gives it a time slice (on a single-core board a busy process,
// the soft PLC for one, otherwise makes it lose edges; an E-stop edge would wait as well).
// Real-time, below the pulse thread; set after the other threads have been started so that
// they do not inherit it. The simulated machine's FIFO is sized to ride out an ordinary thread's
// stalls instead (gpio::kDefaultSimEventRing): the daemon does not call this for it.
void raise_control_thread(int rt_priority) {
  sched_param sp{};
  sp.sched_priority = std::max(1, rt_priority - 10);
  const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
  if (rc != 0) {
    spdlog::warn(
        "control thread: SCHED_FIFO priority {} refused ({}); input edges may be lost "
        "under load",
        sp.sched_priority, std::strerror(rc));
  }
}

}  // namespace stepmod::tools

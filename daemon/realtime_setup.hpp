#pragma once
// The daemon's real-time threads set up from the configuration ([rt] priority, cpu), and what
// the system refused said once in the log (the pulse thread itself never logs). The priorities,
// highest first: pulse thread ([rt] priority), control thread (10 below), planner thread (20
// below), trace thread (1, gpio/vcd_trace.hpp). Main thread (the one that runs Daemon::run).
#include "config/config.hpp"
#include "planner/planner_thread.hpp"
#include "rt/step_output.hpp"

namespace stepmod::tools {

// The pulse thread's options from the configuration.
rt::StepOutput::Options pulse_options(const Config& config);
// What the pulse thread's setup was refused (SCHED_FIFO, mlockall, the CPU pinning).
void warn_pulse_setup(const rt::StepOutput::Options& po, const rt::StepOutput::Status& st);
// The planner thread real-time below the control thread; no-op at `rt_priority` 0.
void raise_planner_thread(planner::PlannerThread& planner, int rt_priority);
// The calling thread (the control thread to be) real-time below the pulse thread.
void raise_control_thread(int rt_priority);

}  // namespace stepmod::tools

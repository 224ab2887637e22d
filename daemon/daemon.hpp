#pragma once
// stepmodd's body: builds a rack of modules (docs/interface.md section 7; a module file is a rack
// of one) from its configuration: each module's backend, shared-memory image and control loop,
// the stack and the trace; runs one control thread per module, one planner thread and one pulse
// thread for them all, and tears all of it down so that the outputs end idle and nothing is left
// in /dev/shm. The parts, one job each:
//   backend_factory   the GPIO backend ([gpio] backend) of a module
//   stack             the layers wired without threads (each module_stack: module, planner;
//                     the one step output)
//   module_runtime    a module's image, panel, Modbus server and control loop
//   daemon_trace      the --trace VCD: rings, writer, losses
//   sim_panel_link    the simulator panel wired to the simulated machine
//   control_loop      the control thread: events, scans and what follows each scan
//                     (lost_input_watch, drive_enable_feed, health_words, charge_pump_feed,
//                     cpu_notice, pulse_doorbell, supervision_log, lease_keeper,
//                     reason_publisher)
//   realtime_setup    the threads' priorities and what the system refused
#include <atomic>
#include <memory>
#include <optional>
#include <string>

#include "config/rack_config.hpp"

namespace stepmod::tools {

class Daemon {
 public:
  // Main thread. Builds everything (throws std::runtime_error with a clear message naming the
  // module; nothing is left behind).
  Daemon(const RackConfig& rack, const std::optional<std::string>& trace_path);
  ~Daemon();
  Daemon(const Daemon&) = delete;
  Daemon& operator=(const Daemon&) = delete;

  // Main thread, which becomes the first module's control thread. Starts the threads and
  // returns when `stop` becomes true (or throws when a module's control thread failed), after the
  // orderly shutdown: immediate stop of every axis, outputs idle, trace written. false if the trace
  // lost records (the VCD says so; stepmodd then exits with status 3).
  bool run(const std::atomic<bool>& stop);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace stepmod::tools

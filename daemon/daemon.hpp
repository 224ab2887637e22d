#pragma once
// stepmodd's body: builds the backend, the shared-memory image, the stack and the trace from a
// configuration, runs the control, planner and pulse threads, and tears all of it down so that
// the outputs end idle and nothing is left in /dev/shm. The parts, one job each:
//   backend_factory   the GPIO backend ([gpio] backend)
//   stack             the layers wired without threads (module, planner, step output)
//   daemon_trace      the --trace VCD: rings, writer, losses
//   sim_panel_link    the simulator panel wired to the simulated machine
//   control_loop      the control thread: events, scans and what follows each scan
//                     (lost_input_watch, drive_enable_feed, health_words, cpu_notice,
//                     pulse_doorbell, supervision_log, lease_keeper, reason_publisher)
//   realtime_setup    the threads' priorities and what the system refused
#include <atomic>
#include <memory>
#include <optional>
#include <string>

#include "config/config.hpp"

namespace stepmod::tools {

class Daemon {
 public:
  // Main thread. Builds everything (throws std::runtime_error with a clear message; nothing is
  // left behind).
  Daemon(const Config& config, const std::optional<std::string>& trace_path);
  ~Daemon();
  Daemon(const Daemon&) = delete;
  Daemon& operator=(const Daemon&) = delete;

  // Main thread, which becomes the control thread. Starts the threads and returns when `stop`
  // becomes true, after the orderly shutdown: immediate stop of every axis, outputs idle, trace
  // written. false if the trace lost records (the VCD says so; stepmodd then exits with status 3).
  bool run(const std::atomic<bool>& stop);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace stepmod::tools

#pragma once
// stepmodd's body: builds the backend, the shared-memory image, the stack and the trace from a
// configuration, runs the control, planner and pulse threads, and tears all of it down so that
// the outputs end idle and nothing is left in /dev/shm.
#include <atomic>
#include <memory>
#include <optional>
#include <string>

#include "config/config.hpp"

namespace stepmod::tools {

class Daemon {
 public:
  // Builds everything (throws std::runtime_error with a clear message; nothing is left behind).
  Daemon(const Config& config, const std::optional<std::string>& trace_path);
  ~Daemon();
  Daemon(const Daemon&) = delete;
  Daemon& operator=(const Daemon&) = delete;

  // Starts the threads and returns when `stop` becomes true, after the orderly shutdown:
  // immediate stop of every axis, outputs idle, trace written. false if the trace lost records
  // (the VCD says so; stepmodd then exits with status 3).
  bool run(const std::atomic<bool>& stop);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace stepmod::tools

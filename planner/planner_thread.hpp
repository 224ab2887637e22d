#pragma once
// The planner thread: Planner::service(now), then sleep until the time it asked for or until a
// command is submitted (the planner's wake counter changes). In a rack it serves every module's
// planner, which then share one wake counter (PlannerOptions::wake_counter).
#include <atomic>
#include <thread>
#include <vector>

#include "planner/planner.hpp"

namespace stepmod::planner {

class PlannerThread {
 public:
  explicit PlannerThread(Planner& planner) : planners_{&planner} {}
  // Every planner's wake counter must be the first's (throws std::invalid_argument).
  explicit PlannerThread(std::vector<Planner*> planners);
  ~PlannerThread() { stop(); }
  PlannerThread(const PlannerThread&) = delete;
  PlannerThread& operator=(const PlannerThread&) = delete;

  void start();
  // Wakes the thread and joins it. Idempotent.
  void stop() noexcept;
  bool running() const noexcept { return thread_.joinable(); }
  // After start(): SCHED_FIFO at `priority` (issue 18: a planner thread at normal priority is
  // held off its CPU for milliseconds by CPU hogs, its pulse thread's 4 ms of edges run dry, and
  // the step train pauses). Returns 0 or the error.
  int set_realtime(int priority) noexcept;
  // Number of service() calls so far (diagnostics, tests).
  std::uint64_t loops() const noexcept { return loops_.load(std::memory_order_relaxed); }

 private:
  void run() noexcept;

  std::vector<Planner*> planners_;  // at least one
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> loops_{0};
};

}  // namespace stepmod::planner

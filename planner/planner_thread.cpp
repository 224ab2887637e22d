#include "planner/planner_thread.hpp"

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <cerrno>
#include <stdexcept>

#include "core/clock.hpp"
#include "planner/wakeup.hpp"

namespace stepmod::planner {

PlannerThread::PlannerThread(std::vector<Planner*> planners) : planners_(std::move(planners)) {
  if (planners_.empty()) throw std::invalid_argument("a planner thread needs a planner");
  for (Planner* p : planners_) {
    if (&p->wake_counter() != &planners_.front()->wake_counter()) {
      throw std::invalid_argument("the planners of one thread must share their wake counter");
    }
  }
}

void PlannerThread::start() {
  if (thread_.joinable()) return;
  stop_.store(false, std::memory_order_relaxed);
  thread_ = std::thread([this] { run(); });
  pthread_setname_np(thread_.native_handle(), "stepmod-plan");
}

void PlannerThread::stop() noexcept {
  if (!thread_.joinable()) return;
  stop_.store(true, std::memory_order_release);
  bump_and_wake(planners_.front()->wake_counter());
  thread_.join();
}

void PlannerThread::run() noexcept {
  std::atomic<std::uint32_t>& wake = planners_.front()->wake_counter();
  while (!stop_.load(std::memory_order_acquire)) {
    // Read the counter before servicing: a submit during service() changes it, so the wait
    // below returns at once instead of sleeping on a queued command.
    const std::uint32_t seen = wake.load(std::memory_order_acquire);
    const Nanos now = monotonic_now();
    Nanos next = rt::kNever;
    for (Planner* p : planners_) next = std::min(next, p->service(now));
    loops_.fetch_add(1, std::memory_order_relaxed);
    if (stop_.load(std::memory_order_acquire)) break;
    if (next > monotonic_now()) wait_for_change(wake, seen, next);
  }
}

int PlannerThread::set_realtime(int priority) noexcept {
  if (!thread_.joinable()) return ESRCH;
  sched_param sp{};
  sp.sched_priority = priority;
  return pthread_setschedparam(thread_.native_handle(), SCHED_FIFO, &sp);
}

}  // namespace stepmod::planner

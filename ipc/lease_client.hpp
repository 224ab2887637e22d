#pragma once
// The commissioning lease kept by a thread (docs/interface.md 3.5, docs/commissioning.md): for a
// tool whose process being alive is the deadman (stepmodctl --wait holds it while it waits on its
// motion, so that the daemon stops the axes if the tool dies or hangs). It is ipc::Lease
// (ipc/lease.hpp, the one lease implementation) plus the check that no PLC is in control and a
// thread that renews it every 50 ms while held.
//
// The renewer runs at SCHED_FIFO when the process may (root, CAP_SYS_NICE or RLIMIT_RTPRIO): the
// daemon's watcher is its control thread, itself SCHED_FIFO, and a renewer at normal priority
// held off the CPU for the lease's 350 ms of slack (CI's Debian 13 stage: ctest -j 2 on two
// cores, test daemons' real-time threads beside other tests) had its lease expire and the axis
// stop mid-move. Watchdog daemons do the same for the same reason. It wakes for a few
// microseconds every 50 ms.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>

#include "ipc/client.hpp"
#include "ipc/lease.hpp"

namespace stepmod::ipc {

class LeaseClient {
 public:
  static constexpr std::chrono::milliseconds kAhead = Lease::kAhead;
  static constexpr std::chrono::milliseconds kRenewEvery{50};
  static_assert(kRenewEvery < Lease::kRenewAtLeastEvery);
  // Above every normal thread and stepmodd's trace writer (SCHED_FIFO 1), below its planner,
  // control and pulse threads at the default [rt] priority (60, 70, 80).
  static constexpr int kRenewerPriority = 5;

  // `pid`: the holder id written into the image (this process' by default).
  explicit LeaseClient(Client& client, std::uint32_t pid = 0);
  ~LeaseClient();  // releases
  LeaseClient(const LeaseClient&) = delete;
  LeaseClient& operator=(const LeaseClient&) = delete;

  enum class Take : std::uint8_t {
    kTaken,         // held from now on, renewed until release()
    kPlcInControl,  // the PLC heartbeat moved within `quiet` (and is not reported stale)
    kHeldByOther,   // another tool holds it
  };
  // Takes the lease if no PLC is in control: the daemon reports the heartbeat stale (health
  // bit 1, after [module] plc_timeout_ms), or the heartbeat does not change for `quiet` (watched
  // here; the contract's 1 s when plc_timeout_ms is 0). Then renews it from a thread.
  Take take(std::chrono::milliseconds quiet = std::chrono::milliseconds(1000));
  // The same, but taking the lease over from holder `from` (stepmodctl --steal, the operator's
  // explicit choice; the daemon logs it). kHeldByOther: `from` no longer holds it.
  Take take_over(std::uint32_t from,
                 std::chrono::milliseconds quiet = std::chrono::milliseconds(1000));
  // Stops renewing and gives the lease back (writes 0 if still ours). Idempotent.
  void release();
  // Ours, as far as the image says (the daemon frees an expired lease).
  bool held() const noexcept { return lease_.held(); }
  // The renewer runs at SCHED_FIFO kRenewerPriority (false: the process may not, or not taken).
  bool renewer_realtime() const noexcept { return renewer_realtime_; }
  std::uint32_t pid() const noexcept { return lease_.id(); }

 private:
  bool plc_quiet(std::chrono::milliseconds quiet) const;
  Take start(std::uint32_t from, std::chrono::milliseconds quiet);
  void renew_loop();

  Client& client_;
  Lease lease_;
  std::mutex m_;
  std::condition_variable cv_;
  bool stop_ = false;
  bool taken_ = false;
  bool renewer_realtime_ = false;
  std::thread renewer_;
};

}  // namespace stepmod::ipc

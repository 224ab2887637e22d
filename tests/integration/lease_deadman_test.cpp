// Issue 29, "The deadman must hold": the commissioning lease (docs/commissioning.md) end to end,
// the real stepmodd and stepmodctl on the simulated 3601. Only a live holder keeps a lease: a tool
// retrying its take cannot push a dead holder's deadline, an expiry no live holder writes is
// expired at once, and no lease word switches off the PLC heartbeat watchdog. The lease excludes:
// a second tool is refused with the holder's pid unless it takes the lease over with --steal
// (logged), and a stop is never refused.
//
// Timing bounds are generous (a loaded 2-core VM): the lease lasts at most 500 ms without renewal;
// a stop "in time" is asserted within 1.5 s, a defect shows as several seconds or never.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <limits>
#include <string>
#include <thread>

#include "ipc/client.hpp"
#include "ipc/lease.hpp"
#include "tests/support/commissioning_daemon.hpp"

namespace stepmod::testing {
namespace {

using std::chrono::milliseconds;

constexpr const char* kConfigure = "configure --home --cw-limit --ccw-limit --estop";
// 18 s at 5000 steps/s: still running at the end of every test below unless something stops it.
constexpr const char* kLongMove = "move rel 90000 -s 5000 -a 100 -d 100 --wait";

class LeaseDeadman : public ::testing::Test {
 protected:
  void start(int plc_timeout_ms = 0) {
    d_ = std::make_unique<CommissioningDaemon>(plc_timeout_ms);
    ASSERT_TRUE(d_->ready()) << d_->log();
    ASSERT_EQ(d_->ctl(kConfigure).exit_status, 0);
  }
  // A `stepmodctl ... --wait` long move, running and holding the lease; its pid.
  pid_t holder_moving() {
    const pid_t tool = d_->ctl_background(kLongMove);
    const bool up =
        eventually([&] { return d_->holder() == static_cast<std::uint32_t>(tool) && d_->moving(); },
                   milliseconds(10'000));
    EXPECT_TRUE(up) << d_->log();
    return up ? tool : -1;
  }
  void TearDown() override {
    if (tool_ > 0) kill_and_reap(tool_);
  }
  std::unique_ptr<CommissioningDaemon> d_;
  pid_t tool_ = -1;
};

std::uint64_t expiry(const ipc::Client& c) {
  return __atomic_load_n(&c.raw().lease_expiry_ns, __ATOMIC_ACQUIRE);
}

// Before the fix a take wrote the expiry before its compare-and-swap: a page retrying "Take
// control" kept a SIGKILLed holder's lease, and its axis, going as long as it retried.
TEST_F(LeaseDeadman, RetriedTakeDoesNotKeepAKilledHoldersAxisMoving) {
  start();
  tool_ = holder_moving();
  ASSERT_GT(tool_, 0);
  const ipc::Client watcher(d_->name());
  std::atomic<bool> stop{false};
  std::atomic<std::uint64_t> takes{0};
  std::thread retrier([&] {  // a live tool that wants the lease: take() every 10 ms
    ipc::Client c(d_->name());
    ipc::Lease lease(c);
    while (!stop) {
      lease.take();
      ++takes;
      std::this_thread::sleep_for(milliseconds(10));
    }
  });
  ASSERT_TRUE(eventually([&] { return takes > 5; }, milliseconds(2000)));
  const std::uint32_t dead = static_cast<std::uint32_t>(tool_);
  kill_and_reap(tool_);
  tool_ = -1;
  const std::uint64_t last = expiry(watcher);  // the dead holder's last renewal
  std::uint64_t pushed = 0;  // the furthest expiry seen while the dead pid still held the lease
  const long long took = d_->ms_until_stopped(milliseconds(4000));
  EXPECT_TRUE(eventually(
      [&] {
        if (d_->holder() != dead) return true;
        pushed = std::max(pushed, expiry(watcher));
        return false;
      },
      milliseconds(2000)));
  stop = true;
  retrier.join();
  ASSERT_GE(took, 0) << "the axis still moved 4 s after its holder was SIGKILLed\n" << d_->log();
  EXPECT_LT(took, 1500) << "stopped " << took << " ms after the kill";
  EXPECT_LE(pushed, last) << "a take moved the dead holder's expiry";
  EXPECT_NE(d_->log().find("commissioning lease of pid " + std::to_string(dead) +
                           " expired without release"),
            std::string::npos)
      << d_->log();
  EXPECT_NE(d_->ctl("status --brief").out.find("3601-PI-S2"), std::string::npos);
  std::printf("[ observed ] stopped %lld ms after the holder's SIGKILL, %llu takes retried\n", took,
              static_cast<unsigned long long>(takes.load()));
}

// An expiry no live holder writes (the contract: at most 500 ms ahead of CLOCK_MONOTONIC) is
// expired at once: stop, free, health bit 6. Before the fix each of them never expired.
TEST_F(LeaseDeadman, ExpiryTooFarAheadIsExpiredAtOnce) {
  start();
  timespec rt{};
  ::clock_gettime(CLOCK_REALTIME, &rt);
  const std::uint64_t realtime = static_cast<std::uint64_t>(rt.tv_sec) * 1'000'000'000u +
                                 static_cast<std::uint64_t>(rt.tv_nsec);
  const struct {
    const char* what;
    std::uint64_t expiry;
  } cases[] = {
      {"10 s ahead", static_cast<std::uint64_t>(stepmod_monotonic_ns() + 10'000'000'000)},
      {"CLOCK_REALTIME + 400 ms", realtime + 400'000'000u},
      {"INT64_MAX", static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    tool_ = holder_moving();
    ASSERT_GT(tool_, 0);
    // Frozen (no more renewals), then the garbage, then dead: only the garbage can keep it.
    ::kill(tool_, SIGSTOP);
    ipc::Client w(d_->name());
    __atomic_store_n(&w.writable_image().lease_expiry_ns, c.expiry, __ATOMIC_RELEASE);
    kill_and_reap(tool_);
    tool_ = -1;
    const long long took = d_->ms_until_stopped(milliseconds(3000));
    ASSERT_GE(took, 0) << "still moving 3 s after an expiry " << c.what << "\n" << d_->log();
    EXPECT_LT(took, 1500);
    EXPECT_EQ(d_->holder(), 0u);
    EXPECT_TRUE(d_->health() & STEPMOD_HEALTH_LEASE_EXPIRED);
    std::printf("[ observed ] expiry %s: stopped in %lld ms\n", c.what, took);
    ASSERT_EQ(d_->ctl("reset").exit_status, 0);
  }
  EXPECT_NE(d_->log().find("ms ahead, more than the 500 ms a live holder writes"),
            std::string::npos)
      << d_->log();
}

// Before the fix any held lease reset the PLC heartbeat timer at every scan: garbage lease words
// switched the PLC watchdog off, and an axis moved on after its PLC died.
TEST_F(LeaseDeadman, GarbageLeaseWordsDoNotSwitchOffThePlcWatchdog) {
  start(300);
  std::atomic<bool> plc_alive{true};
  std::thread plc([&] {
    ipc::Client c(d_->name());
    while (plc_alive) {
      c.heartbeat();
      std::this_thread::sleep_for(milliseconds(10));
    }
  });
  ASSERT_TRUE(eventually([&] { return (d_->health() & STEPMOD_HEALTH_PLC_STALE) == 0; },
                         milliseconds(3000)));
  ASSERT_EQ(d_->ctl("move rel 90000 -s 5000 -a 100 -d 100").exit_status, 0);  // the PLC's move
  ASSERT_TRUE(eventually([&] { return d_->moving(); }, milliseconds(3000)));
  // A complete take (sequence incremented) with a holder that runs and an expiry of 2^63-1.
  ipc::Client w(d_->name());
  stepmod_image_t& img = w.writable_image();
  __atomic_store_n(&img.lease_expiry_ns, static_cast<std::uint64_t>(INT64_MAX), __ATOMIC_RELEASE);
  __atomic_store_n(&img.lease_holder, static_cast<std::uint32_t>(::getpid()), __ATOMIC_RELEASE);
  __atomic_fetch_add(&img.lease_seq, 1u, __ATOMIC_ACQ_REL);
  std::this_thread::sleep_for(milliseconds(50));
  plc_alive = false;  // the PLC dies
  plc.join();
  const auto died = Clock::now();
  const bool stale = eventually([&] { return (d_->health() & STEPMOD_HEALTH_PLC_STALE) != 0; },
                                milliseconds(3000));
  const auto ms = std::chrono::duration_cast<milliseconds>(Clock::now() - died).count();
  ASSERT_TRUE(stale) << "no PLC-stale bit 3 s after the PLC died (plc_timeout_ms 300)\n"
                     << d_->log();
  EXPECT_LT(ms, 2000);
  const long long stopped = d_->ms_until_stopped(milliseconds(2000));
  EXPECT_GE(stopped, 0) << d_->log();
  EXPECT_NE(d_->log().find("expired without release"), std::string::npos) << d_->log();
  std::printf("[ observed ] PLC stale %lld ms after it died\n", static_cast<long long>(ms));
}

// ---- the lease excludes ------------------------------------------------------------------------

// Before the fix the second tool said "waiting without it" and wrote its command anyway.
TEST_F(LeaseDeadman, SecondWaitingStepmodctlIsRefusedNamingTheHolder) {
  start();
  tool_ = holder_moving();
  ASSERT_GT(tool_, 0);
  const ipc::Client c(d_->name());
  ImageWords before{};
  ImageWords after{};
  ASSERT_TRUE(c.read_outputs(before));
  const CtlRun r = d_->ctl("move rel 3000 -s 5000 -a 100 -d 100 --wait");
  ASSERT_TRUE(c.read_outputs(after));
  EXPECT_EQ(r.exit_status, 1) << r.err;
  EXPECT_NE(r.err.find("held by pid " + std::to_string(tool_) + " (running)"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("--steal"), std::string::npos) << r.err;
  EXPECT_TRUE(before == after) << "the refused command wrote the output words";
  EXPECT_EQ(d_->holder(), static_cast<std::uint32_t>(tool_));
  EXPECT_TRUE(d_->moving());
}

// The operator's explicit override: the lease changes hands, both programs log it.
TEST_F(LeaseDeadman, StealTakesTheLeaseOverAndIsLogged) {
  start();
  tool_ = holder_moving();
  ASSERT_GT(tool_, 0);
  const std::string victim = std::to_string(tool_);
  const CtlRun r = d_->ctl("--steal hold");
  EXPECT_EQ(r.exit_status, 0) << r.err << r.out;
  EXPECT_NE(r.err.find("--steal: the commissioning lease of module '" + d_->name() +
                       "' taken over from pid " + victim),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(eventually(
      [&] {
        return d_->log().find("commissioning lease of pid " + victim + " taken over by pid") !=
               std::string::npos;
      },
      milliseconds(2000)))
      << d_->log();
  EXPECT_GE(d_->ms_until_stopped(milliseconds(2000)), 0);  // held
  // The old holder's wait ends (its move did not complete); the lease went with the stealer.
  const int old_holder = reap_within(tool_, milliseconds(5000));
  EXPECT_EQ(old_holder, 1);
  if (old_holder >= 0) tool_ = -1;
  EXPECT_EQ(d_->holder(), 0u);
  EXPECT_EQ(d_->log().find("expired without release"), std::string::npos) << d_->log();
}

// A stop is never refused, and under another tool's lease it is no PLC: no heartbeat, so no
// false "two writers" (before the fix it bumped the heartbeat: health bit 7 and that warning).
TEST_F(LeaseDeadman, StepmodctlStopWorksWhileAnotherProcessHoldsTheLease) {
  start();
  tool_ = holder_moving();
  ASSERT_GT(tool_, 0);
  const CtlRun r = d_->ctl("stop");
  EXPECT_EQ(r.exit_status, 0) << r.err;
  EXPECT_EQ(r.err.find("refused"), std::string::npos) << r.err;
  const long long took = d_->ms_until_stopped(milliseconds(2000));
  EXPECT_GE(took, 0) << d_->log();
  const int old_holder = reap_within(tool_, milliseconds(5000));
  EXPECT_EQ(old_holder, 1);  // its move ended in a stop
  if (old_holder >= 0) tool_ = -1;
  EXPECT_EQ(d_->log().find("two writers"), std::string::npos) << d_->log();
  EXPECT_EQ(d_->log().find("taken over"), std::string::npos) << d_->log();
  std::printf("[ observed ] stopped %lld ms after stepmodctl stop returned\n", took);
}

}  // namespace
}  // namespace stepmod::testing

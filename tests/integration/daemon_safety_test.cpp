// End to end, issue 12: the real stepmodd stalled (SIGSTOP), a PLC that stops beating, dies in
// the middle of a write or bypasses the seqlock, and a daemon that finds a crashed one's image.
// Assertions are on structure (a fault flagged, no burst, nothing moved) rather than tight
// timing, so they hold on a loaded two-core machine and under the sanitizers.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <limits>
#include <thread>

#include "ipc/sim_panel.hpp"
#include "tests/support/daemon_process.hpp"
#include "tests/support/shm_plc_3601.hpp"
#include "tests/support/sim_config.hpp"
#include "tests/support/vcd_reader.hpp"

namespace stepmod::testing {
namespace {

namespace m = words::m3601;
using namespace m::status_msw;
namespace cmd = m::cmd_msw;
using std::chrono::milliseconds;

// No simulated encoder: its input edge per step is a load of the simulation (a million events
// a second into the control thread at 1 MHz), not of the trace this file tests.
constexpr const char* kSim = R"(cw_limit_at = 10000000
ccw_limit_at = -10000000
encoder_ratio = 0.0
)";

class DaemonSafety : public ::testing::Test {
 protected:
  void start(const std::string& module_extra = "", const std::string& name = "",
             const std::string& rt_extra = kRelaxedLateLimit,
             const std::string& axis_extra = kRelaxedLagLimit) {
    daemon_ = std::make_unique<DaemonProcess>(
        sim_3601_config(module_extra, kSim, rt_extra, axis_extra), true, name);
    ASSERT_TRUE(daemon_->wait_ready()) << daemon_->log();
    plc_ = std::make_unique<RawShmPlc>(daemon_->name());
  }
  Vcd stop_and_read_trace() {
    plc_.reset();
    EXPECT_EQ(daemon_->terminate(), 0) << daemon_->log();
    return read_vcd(daemon_->trace_path());
  }
  ipc::Health health() { return plc_->client().read_health(); }
  std::int64_t motor() {
    ipc::SimPanelClient panel(daemon_->name());
    return panel.read(0).position;
  }
  // The image, writable as a misbehaving PLC would write it.
  stepmod_image_t& raw() { return const_cast<stepmod_image_t&>(plc_->client().raw()); }

  std::unique_ptr<DaemonProcess> daemon_;
  std::unique_ptr<RawShmPlc> plc_;
};

// Most steps in any window of `window` ns.
std::size_t densest(const std::vector<std::int64_t>& t, std::int64_t window) {
  std::size_t best = 0;
  std::size_t lo = 0;
  for (std::size_t hi = 0; hi < t.size(); ++hi) {
    while (t[hi] - t[lo] >= window) ++lo;
    best = std::max(best, hi - lo + 1);
  }
  return best;
}

TEST_F(DaemonSafety, SigstopMidMoveIsALateEdgeFaultNeverABurst) {
  start("", "", kDefaultLateLimit, "");
  plc_->configure();
  plc_->command(cmd::kPresetPosition, 0);
  // 20,000 steps/s (50 us periods), 200,000 steps: ~10 s if nothing stopped it.
  plc_->command(cmd::kRelativeMove, 200'000, 20'000, 200, 200);
  // Well into the move -- or already stopped by a fault of its own: on a loaded machine the
  // pulse thread may be stalled beyond the limit without our help; what follows holds either way.
  ASSERT_TRUE(
      plc_->wait([&] { return plc_->position() > 5'000 || !plc_->moving(); }, milliseconds(5'000)))
      << daemon_->log();
  daemon_->signal(SIGSTOP);
  std::this_thread::sleep_for(milliseconds(200));
  daemon_->signal(SIGCONT);
  ASSERT_TRUE(plc_->wait([&] { return !plc_->moving(); }, milliseconds(5'000))) << daemon_->log();
  EXPECT_TRUE(plc_->status(kStopped));
  EXPECT_TRUE(plc_->status(kPositionInvalid));
  EXPECT_FALSE(plc_->status(kMoveComplete));
  const ipc::Health h = health();
  EXPECT_GE(h.late_faults, 1u);
  EXPECT_NE(h.flags & STEPMOD_HEALTH_LATE_EDGE, 0u);
  EXPECT_GE(h.worst_late_us, 400u);  // the pause: > 8 steps at 20,000 steps/s (lag limit)
  const std::int64_t position = plc_->position();
  EXPECT_LT(position, 200'000);
  const std::string log = daemon_->log();
  EXPECT_NE(log.find("axis 1: late-edge fault"), std::string::npos) << log;

  const Vcd vcd = stop_and_read_trace();
  const auto steps = vcd.rising("axis1.step");
  // The count is exact: every pulse on the line is one the position counts.
  EXPECT_EQ(static_cast<std::int64_t>(steps.size()), position);
  // No burst: at 20,000 steps/s a millisecond holds 20 steps, and late edges slip (issue 18),
  // never catch up. 4,000 steps were due in the stall: a burst puts them together.
  EXPECT_LE(densest(steps, 1'000'000), 25u);
}

// Issue 18: at the starting speed a pause is harmless. A daemon stopped for 50 ms (SIGSTOP: the
// fair server's longest pause on a 6.12+ kernel) slips the move and completes it, with the
// product's guard; stopped for 400 ms (beyond [rt] late_limit_us, 200 ms) it faults the axis.
std::int64_t shortest_gap(const std::vector<std::int64_t>& t) {
  std::int64_t gap = std::numeric_limits<std::int64_t>::max();
  for (std::size_t i = 1; i < t.size(); ++i) gap = std::min(gap, t[i] - t[i - 1]);
  return gap;
}

TEST_F(DaemonSafety, ShortSigstopAtTheStartingSpeedSlipsTheMoveWithoutAFault) {
#if defined(STEPMOD_SANITIZED)
  // Under the sanitizers the pulse thread's own stalls exceed 200 ms now and then: the pause
  // limit relaxed (at Vs the lag is not judged, so the test still shows slip without a fault).
  start("", "", kRelaxedLateLimit, "");
#else
  start("", "", kDefaultLateLimit, "");
#endif
  plc_->configure(2'000);  // Vs = 2,000 steps/s
  plc_->command(cmd::kPresetPosition, 0);
  plc_->command(cmd::kRelativeMove, 3'000, 2'000, 10, 10);  // all at Vs: 1.5 s
  ASSERT_TRUE(
      plc_->wait([&] { return plc_->position() > 500 || !plc_->moving(); }, milliseconds(5'000)))
      << daemon_->log();
  daemon_->signal(SIGSTOP);
  std::this_thread::sleep_for(milliseconds(50));
  daemon_->signal(SIGCONT);
  ASSERT_TRUE(plc_->wait([&] { return !plc_->moving(); }, milliseconds(10'000))) << daemon_->log();
  EXPECT_TRUE(plc_->status(kMoveComplete)) << daemon_->log();
  EXPECT_FALSE(plc_->status(kPositionInvalid));
  EXPECT_EQ(plc_->position(), 3'000);
  EXPECT_EQ(health().late_faults, 0u) << daemon_->log();
  const Vcd vcd = stop_and_read_trace();
  const auto steps = vcd.rising("axis1.step");
  EXPECT_EQ(steps.size(), 3'000u);
  // Never squeezed: no interval shorter than Vs's 500 us (less the 2 us write allowance).
  EXPECT_GE(shortest_gap(steps), 498'000);
}

TEST_F(DaemonSafety, LongSigstopAtTheStartingSpeedIsALateEdgeFault) {
  start("", "", kDefaultLateLimit, "");
  plc_->configure(2'000);
  plc_->command(cmd::kPresetPosition, 0);
  plc_->command(cmd::kRelativeMove, 6'000, 2'000, 10, 10);  // all at Vs: 3 s
  ASSERT_TRUE(
      plc_->wait([&] { return plc_->position() > 500 || !plc_->moving(); }, milliseconds(5'000)))
      << daemon_->log();
  daemon_->signal(SIGSTOP);
  std::this_thread::sleep_for(milliseconds(400));
  daemon_->signal(SIGCONT);
  ASSERT_TRUE(plc_->wait([&] { return !plc_->moving(); }, milliseconds(5'000))) << daemon_->log();
  EXPECT_TRUE(plc_->status(kPositionInvalid));
  EXPECT_FALSE(plc_->status(kMoveComplete));
  const ipc::Health h = health();
#if defined(STEPMOD_SANITIZED)
  // A sanitized daemon on a loaded machine can stall past the limit once more on its own.
  EXPECT_GE(h.late_faults, 1u) << daemon_->log();
#else
  // The log names each fault's step and pause: a second one is told apart from the first there.
  EXPECT_EQ(h.late_faults, 1u) << daemon_->log();
#endif
  EXPECT_GE(h.worst_late_us, 200'000u);
  const std::string log = daemon_->log();
  EXPECT_NE(log.find("axis 1: late-edge fault at step"), std::string::npos) << log;
  EXPECT_NE(log.find("lag 0 steps"), std::string::npos) << log;  // at Vs: judged by the pause
  const std::int64_t position = plc_->position();
  const Vcd vcd = stop_and_read_trace();
  EXPECT_EQ(static_cast<std::int64_t>(vcd.rising("axis1.step").size()), position);
}

TEST_F(DaemonSafety, StaleHeartbeatKeepsTheModuleStoppedAndIgnoresNewCommands) {
  start("plc_timeout_ms = 200");
  std::atomic<bool> beating{true};
  std::thread heart([&] {
    while (beating) {
      plc_->client().heartbeat();
      std::this_thread::sleep_for(milliseconds(10));
    }
  });
  plc_->configure();
  plc_->command(cmd::kPresetPosition, 0);
  plc_->command(cmd::kRelativeMove, 500'000, 10'000, 10, 10);
  ASSERT_TRUE(plc_->wait([&] { return plc_->position() > 100; }, milliseconds(3'000)));
  beating = false;
  heart.join();
  ASSERT_TRUE(plc_->wait([&] { return !plc_->moving(); }, milliseconds(3'000)));
  EXPECT_TRUE(plc_->status(kPositionInvalid));
  EXPECT_NE(health().flags & STEPMOD_HEALTH_PLC_STALE, 0u);
  const std::int64_t rest = motor();

  // With the heartbeat still stale, a new relative move is written: nothing moves.
  plc_->write(cmd::kRelativeMove, 0, 5'000, 10'000, 10, 10);
  plc_->scans(300);
  EXPECT_EQ(motor(), rest);
  EXPECT_FALSE(plc_->moving());
  EXPECT_NE(health().flags & STEPMOD_HEALTH_PLC_STALE, 0u);
  plc_->write(0, 0, 0, 0, 0, 0);
  plc_->scans(5);

  // The heartbeat moves again: the flag clears; a new command edge is acted on.
  beating = true;
  std::thread heart2([&] {
    while (beating) {
      plc_->client().heartbeat();
      std::this_thread::sleep_for(milliseconds(10));
    }
  });
  ASSERT_TRUE(plc_->wait([&] { return (health().flags & STEPMOD_HEALTH_PLC_STALE) == 0; },
                         milliseconds(2'000)));
  EXPECT_EQ(motor(), rest);
  plc_->command(cmd::kRelativeMove, 2'000, 10'000, 10, 10);
  const bool completed =
      plc_->wait([&] { return plc_->status(kMoveComplete); }, milliseconds(5'000));
  beating = false;
  heart2.join();
  EXPECT_TRUE(completed);
  EXPECT_EQ(motor(), rest + 2'000);
  const std::string log = daemon_->log();
  EXPECT_NE(log.find("PLC heartbeat unchanged"), std::string::npos) << log;
  EXPECT_NE(log.find("PLC heartbeat moves again"), std::string::npos) << log;
  stop_and_read_trace();
}

TEST_F(DaemonSafety, SequenceLeftOddStopsAHeldManualMove) {
  start();  // heartbeat watch off: 100 ms of an odd sequence is a dead PLC
  plc_->configure();
  plc_->command(cmd::kPresetPosition, 0);
  plc_->write(cmd::kManualCw, 0, 0, 5'000, 10, 10);  // held: runs until released
  ASSERT_TRUE(plc_->wait([&] { return plc_->position() > 100; }, milliseconds(3'000)));
  // The PLC starts a write (Immediate Stop) and dies before finishing it.
  stepmod_image_t& img = raw();
  const std::uint32_t odd = stepmod_seq_write_begin(&img.output_seq, 0);
  stepmod_word_store(&img.output_image, 2, 0, cmd::kImmediateStop);
  ASSERT_TRUE(plc_->wait([&] { return !plc_->moving(); }, milliseconds(2'000)));
  EXPECT_TRUE(plc_->status(kPositionInvalid));
  EXPECT_NE(health().flags & STEPMOD_HEALTH_SEQ_STUCK, 0u);
  const std::int64_t rest = motor();
  plc_->scans(200);
  EXPECT_EQ(motor(), rest);
  // The write completes: the flag clears.
  stepmod_word_store(&img.output_image, 2, 0, 0);
  stepmod_seq_write_end(&img.output_seq, odd);
  ASSERT_TRUE(plc_->wait([&] { return (health().flags & STEPMOD_HEALTH_SEQ_STUCK) == 0; },
                         milliseconds(2'000)));
  const std::string log = daemon_->log();
  EXPECT_NE(log.find("output sequence left odd"), std::string::npos) << log;
  EXPECT_NE(log.find("output sequence moves again"), std::string::npos) << log;
  stop_and_read_trace();
}

TEST_F(DaemonSafety, WordsWrittenAroundTheSeqlockAreFlagged) {
  start();
  plc_->configure();
  plc_->scans(5);
  EXPECT_EQ(health().flags & STEPMOD_HEALTH_SEQ_BYPASS, 0u);
  // A writer that ignores the sequence: the words change, the sequence does not.
  stepmod_word_store(&raw().output_image, 2, 3, 2'444);
  ASSERT_TRUE(plc_->wait([&] { return (health().flags & STEPMOD_HEALTH_SEQ_BYPASS) != 0; },
                         milliseconds(1'000)));
  // Cleared a second after the last such change.
  ASSERT_TRUE(plc_->wait([&] { return (health().flags & STEPMOD_HEALTH_SEQ_BYPASS) == 0; },
                         milliseconds(3'000)));
  const std::string log = daemon_->log();
  EXPECT_NE(log.find("bypasses the seqlock"), std::string::npos) << log;
  EXPECT_NE(log.find("no seqlock bypass for"), std::string::npos) << log;
  stop_and_read_trace();
}

TEST_F(DaemonSafety, ADaemonThatFindsACrashedOnesImageSaysWhatItReplaced) {
  start();
  plc_->configure();
  const std::string name = daemon_->name();
  const pid_t crashed = daemon_->pid();
  plc_.reset();
  daemon_->signal(SIGKILL);
  ASSERT_GE(daemon_->wait_exit(), 0);
  // The crashed daemon's image is still there: wait_ready() waits until the image names the new
  // daemon as its owner. The crashed one's handle is kept to the end: destroyed now, it would
  // remove the image it left before the new daemon finds it.
  const std::unique_ptr<DaemonProcess> crashed_daemon = std::move(daemon_);
  daemon_ = std::make_unique<DaemonProcess>(sim_3601_config("", kSim), true, name);
  ASSERT_TRUE(daemon_->wait_ready()) << daemon_->log();
  plc_ = std::make_unique<RawShmPlc>(name);
  plc_->scans(3);
  const std::string log = daemon_->log();
  EXPECT_NE(log.find("replaced a stale /dev/shm/stepmod." + name + " of stepmodd pid " +
                     std::to_string(crashed)),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("module 3601"), std::string::npos) << log;
  stop_and_read_trace();
}

// Issue 12 item 4: every output write reaches the VCD, even at 1 MHz (2 M records/s) on a shared
// machine. Under the sanitizers the pulse thread cannot make 1 MHz; there the same check runs at
// a rate it can make.
TEST_F(DaemonSafety, TraceOfAMillionStepsPerSecondMoveIsComplete) {
#if defined(STEPMOD_SANITIZED)
  constexpr std::int32_t kSteps = 100'000, kSpeed = 50'000;
#else
  constexpr std::int32_t kSteps = 2'000'000, kSpeed = 1'000'000;
#endif
  // The trace is under test here, not the guard (its own tests above): the longest limit, so a
  // stall of a sanitizer build on a loaded machine (one cut the move after 200 ms under TSan)
  // does not end the move early.
  start("", "", kRelaxedLateLimit);
  plc_->configure();
  plc_->command(cmd::kPresetPosition, 0);
  plc_->command(cmd::kRelativeMove, kSteps, kSpeed, 2'000, 2'000);
  ASSERT_TRUE(plc_->wait([&] { return !plc_->moving(); }, milliseconds(60'000)));
  EXPECT_TRUE(plc_->status(kMoveComplete)) << daemon_->log();
  EXPECT_EQ(plc_->position(), kSteps);
#if !defined(STEPMOD_SANITIZED)
  // 2 M edges/s: the pulse thread cannot sleep between them, and the daemon says so.
  EXPECT_NE(daemon_->log().find("so the thread stays on its CPU"), std::string::npos)
      << daemon_->log();
#endif
  plc_.reset();
  EXPECT_EQ(daemon_->terminate(), 0) << daemon_->log();  // 3 if the trace had lost records
  const Vcd vcd = read_vcd(daemon_->trace_path());
  EXPECT_EQ(vcd.rising("axis1.step").size(), static_cast<std::size_t>(kSteps));
  EXPECT_EQ(vcd.wires.count("trace.records_lost"), 0u);
}

}  // namespace
}  // namespace stepmod::testing

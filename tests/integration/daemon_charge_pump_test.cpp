// End to end, issue 33: the charge-pump output (an extension; docs/safety.md "Charge pump") of
// the real stepmodd on the simulated 3601, checked in the VCD as a relay board would see it: the
// `charge_pump` wire toggles at its frequency while the module is healthy, and stops (low) on each
// cause -- an E-stop input, a fault (lost input events), the PLC lost, an expired commissioning
// lease, lost trace records, the daemon's stop -- and runs again once a cause is gone. The test
// maps its own CLOCK_MONOTONIC times onto the VCD's by the #0 the daemon logs. Bounds are generous
// (a loaded two-core VM): one scan is 1 ms, a stop is asserted within kReact of its cause.
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <thread>

#include "core/clock.hpp"
#include "daemon/charge_pump_feed.hpp"
#include "ipc/lease.hpp"
#include "ipc/sim_panel.hpp"
#include "tests/support/daemon_process.hpp"
#include "tests/support/shm_plc_3601.hpp"
#include "tests/support/sim_config.hpp"
#include "tests/support/vcd_reader.hpp"

namespace stepmod::testing {
namespace {

namespace cmd = words::m3601::cmd_msw;
using std::chrono::milliseconds;

constexpr const char* kWire = "charge_pump";
constexpr std::int64_t kEdgesPerSecond = 200;  // 100 Hz: two edges a period
// How long after its cause a stop must be seen (50 scans): a loaded machine's late scan, never a
// pump that kept running.
constexpr Nanos kReact = 50 * kNsPerMs;
constexpr Nanos kHold = 600 * kNsPerMs;  // how long each cause is held

std::string config(const std::string& module_extra = "", const std::string& sim = "") {
  return sim_3601_config(module_extra, "cw_limit_at = 10000000\nccw_limit_at = -10000000\n" + sim) +
         "\n[charge_pump]\nline = 22\nfrequency_hz = 100\n";
}

// The daemon's #0 (CLOCK_MONOTONIC), from its log.
Nanos vcd_zero(const std::string& log) {
  std::smatch m;
  if (!std::regex_search(log, m, std::regex("#0 is CLOCK_MONOTONIC ([0-9]+) ns"))) return -1;
  return std::stoll(m[1]);
}

void sleep_ns(Nanos ns) {
  std::this_thread::sleep_for(std::chrono::nanoseconds(ns));
}

// The pump's wire of a finished run, on the test's clock.
struct PumpWire {
  std::vector<VcdChange> changes;  // after #0, times made CLOCK_MONOTONIC
  int initial = -1;

  // Changes in [from, to).
  std::size_t edges(Nanos from, Nanos to) const {
    return static_cast<std::size_t>(std::count_if(
        changes.begin(), changes.end(), [&](const auto& c) { return c.t >= from && c.t < to; }));
  }
  int level_at(Nanos t) const {
    int level = initial;
    for (const VcdChange& c : changes) {
      if (c.t <= t) level = c.level;
    }
    return level;
  }
};

PumpWire pump_wire(DaemonProcess& daemon) {
  PumpWire w;
  const Vcd vcd = read_vcd(daemon.trace_path());
  const Nanos zero = vcd_zero(daemon.log());
  EXPECT_GT(zero, 0) << "no #0 in the log";
  EXPECT_EQ(vcd.wires.count(kWire), 1u) << "no charge_pump wire in the VCD";
  if (vcd.wires.count(kWire) == 0) return w;
  const std::vector<VcdChange>& all = vcd.wires.at(kWire);
  if (all.empty()) return w;
  w.initial = all.front().level;
  for (std::size_t i = 1; i < all.size(); ++i) w.changes.push_back({all[i].t + zero, all[i].level});
  return w;
}

// A stop of the pump held from `cause` (+ `latency`, the daemon's own detection time) to `gone`:
// no edge from kReact after it until the cause is gone, the wire low; running before; running
// again after `gone` when `restarts`.
void expect_stopped_between(const PumpWire& w, Nanos cause, Nanos latency, Nanos gone, Nanos end,
                            bool restarts) {
  const Nanos stopped = cause + latency + kReact;
  EXPECT_GT(w.edges(cause - 300 * kNsPerMs, cause), 20u) << "running before the cause";
  EXPECT_EQ(w.edges(stopped, gone), 0u) << "edges while the cause lasted";
  EXPECT_EQ(w.level_at(stopped), 0) << "held low while stopped";
  if (restarts) {
    EXPECT_GT(w.edges(gone + kReact, end), 20u) << "running again once the cause was gone";
  }
}

// The PLC's heartbeat, beaten every 20 ms while `beating`.
class Heartbeat {
 public:
  explicit Heartbeat(ipc::Client& c)
      : thread_([this, &c] {
          while (!quit_) {
            if (beating_) c.heartbeat();
            std::this_thread::sleep_for(milliseconds(20));
          }
        }) {}
  ~Heartbeat() {
    quit_ = true;
    thread_.join();
  }
  void set(bool on) { beating_ = on; }

 private:
  std::atomic<bool> beating_{true};
  std::atomic<bool> quit_{false};
  std::thread thread_;
};

// Healthy for the whole run: the rate over the run and the stop with the daemon.
TEST(DaemonChargePump, TogglesAtItsFrequencyWhileHealthyAndStopsLowWithTheDaemon) {
  DaemonProcess daemon(config());
  ASSERT_TRUE(daemon.wait_ready()) << daemon.log();
  RawShmPlc plc(daemon.name());
  plc.configure();
  const Nanos from = monotonic_now();
  sleep_ns(2 * kNsPerSec);
  const Nanos to = monotonic_now();
  ASSERT_EQ(daemon.terminate(), 0) << daemon.log();
  const PumpWire w = pump_wire(daemon);
  EXPECT_EQ(w.initial, 0) << "inactive at #0";
  const std::size_t n = w.edges(from, to);
  const auto ideal = static_cast<std::size_t>(kEdgesPerSecond * (to - from) / kNsPerSec);
  // Never faster than the frequency; slower only as far as a loaded machine's scans were late.
  EXPECT_LE(n, ideal + 2) << "edges in " << (to - from) / kNsPerMs << " ms";
  EXPECT_GE(n, ideal / 3) << "edges in " << (to - from) / kNsPerMs << " ms";
  ASSERT_FALSE(w.changes.empty());
  EXPECT_EQ(w.changes.back().level, 0) << "low once the daemon stopped";
  EXPECT_NE(daemon.log().find("charge pump running: 100 Hz, a toggle every 5 scan(s)"),
            std::string::npos)
      << daemon.log();
  std::printf("[ observed ] %zu edges in %lld ms (%zu at exactly 100 Hz)\n", n,
              static_cast<long long>((to - from) / kNsPerMs), ideal);
}

TEST(DaemonChargePump, AnEStopInputStopsItUntilReleased) {
  DaemonProcess daemon(config());
  ASSERT_TRUE(daemon.wait_ready()) << daemon.log();
  RawShmPlc plc(daemon.name());
  ipc::SimPanelClient panel(daemon.name());
  plc.configure();
  sleep_ns(500 * kNsPerMs);
  const Nanos cause = monotonic_now();
  panel.force(0, 3, true);  // E-stop (active high as configured)
  sleep_ns(kHold);
  const Nanos gone = monotonic_now();
  panel.force(0, 3, false);
  sleep_ns(500 * kNsPerMs);
  const Nanos end = monotonic_now();
  ASSERT_EQ(daemon.terminate(), 0) << daemon.log();
  expect_stopped_between(pump_wire(daemon), cause, 0, gone, end, true);
  EXPECT_NE(daemon.log().find("charge pump stopped (E-stop input active)"), std::string::npos)
      << daemon.log();
}

TEST(DaemonChargePump, AStalePlcStopsItUntilItsHeartbeatIsBack) {
  constexpr Nanos kTimeout = 300 * kNsPerMs;
  DaemonProcess daemon(config("plc_timeout_ms = 300\n"));
  ASSERT_TRUE(daemon.wait_ready()) << daemon.log();
  RawShmPlc plc(daemon.name());
  Heartbeat beat(plc.client());
  plc.configure();
  sleep_ns(500 * kNsPerMs);
  const Nanos cause = monotonic_now();
  beat.set(false);
  sleep_ns(kTimeout + kHold);
  const Nanos gone = monotonic_now();
  beat.set(true);
  sleep_ns(500 * kNsPerMs);
  const Nanos end = monotonic_now();
  ASSERT_EQ(daemon.terminate(), 0) << daemon.log();
  const PumpWire w = pump_wire(daemon);
  expect_stopped_between(w, cause, kTimeout, gone, end, true);
  EXPECT_GT(w.edges(cause, cause + kTimeout - kReact), 5u) << "running until the timeout";
  EXPECT_NE(daemon.log().find("charge pump stopped (PLC lost)"), std::string::npos) << daemon.log();
}

TEST(DaemonChargePump, AnExpiredLeaseStopsItUntilTheNextTake) {
  DaemonProcess daemon(config());
  ASSERT_TRUE(daemon.wait_ready()) << daemon.log();
  RawShmPlc plc(daemon.name());
  plc.configure();
  ipc::Client tool(daemon.name());
  ipc::Lease lease(tool);
  ASSERT_TRUE(lease.take());
  for (int i = 0; i < 10; ++i) {  // a live holder for 500 ms
    sleep_ns(50 * kNsPerMs);
    ASSERT_TRUE(lease.renew());
  }
  const Nanos cause = monotonic_now();  // the holder hangs: its lease ends kAhead from now
  const Nanos ahead = std::chrono::nanoseconds(ipc::Lease::kAhead).count();
  sleep_ns(ahead + kHold);
  const Nanos gone = monotonic_now();
  ASSERT_TRUE(lease.take()) << "a new take ends health bit 6";
  sleep_ns(100 * kNsPerMs);  // seen by the daemon's scans
  lease.release();
  sleep_ns(500 * kNsPerMs);
  const Nanos end = monotonic_now();
  ASSERT_EQ(daemon.terminate(), 0) << daemon.log();
  expect_stopped_between(pump_wire(daemon), cause, ahead, gone, end, true);
  EXPECT_NE(daemon.log().find("charge pump stopped (commissioning lease expired)"),
            std::string::npos)
      << daemon.log();
}

// A fault: input events lost (the simulated FIFO of 2 events overflows at the first step, as in
// daemon_lost_input_test.cpp). Its health bit stands until the PLC's next accepted motion; the
// pump stops for the drop time (ChargePumpFeed::FaultDrop) and then runs with the bit standing.
TEST(DaemonChargePump, LostInputEventsStopItForTheDropTime) {
  DaemonProcess daemon(config("", "encoder_ratio = 4\nevent_ring = 2\n"));
  ASSERT_TRUE(daemon.wait_ready()) << daemon.log();
  RawShmPlc plc(daemon.name());
  plc.configure();
  sleep_ns(500 * kNsPerMs);
  const Nanos cause = monotonic_now();
  plc.command(cmd::kRelativeMove, 100'000, 1'000, 200, 200);
  ASSERT_TRUE(
      plc.wait([&] { return (plc.client().read_health().flags & STEPMOD_HEALTH_INPUT_LOST) != 0; },
               milliseconds(5'000)))
      << daemon.log();
  const Nanos lost = monotonic_now();  // seen by the test: at least a scan after the daemon
  constexpr Nanos kDrop = tools::ChargePumpFeed::FaultDrop::kDrop;
  sleep_ns(kDrop + kHold);
  const Nanos end = monotonic_now();
  EXPECT_NE(plc.client().read_health().flags & STEPMOD_HEALTH_INPUT_LOST, 0u) << "bit 5 stands";
  ASSERT_EQ(daemon.terminate(), 0) << daemon.log();
  const PumpWire w = pump_wire(daemon);
  // Stopped from the fault until the drop time after it at the earliest (the fault came after
  // `cause`), running again from the drop time after the test saw it.
  expect_stopped_between(w, cause, lost - cause, cause + kDrop, end, false);
  EXPECT_GT(w.edges(lost + kDrop + kReact, end), 20u) << "running again after the drop time";
  EXPECT_NE(daemon.log().find("charge pump stopped (fault: a late edge or lost input events"),
            std::string::npos)
      << daemon.log();
}

// Lost trace records: a spool that cannot be written (a full 256 KiB tmpfs, as in
// daemon_trace_files_test.cpp). The VCD cannot be written then, so the wire is read where a relay
// would: the simulated line (the panel's output bit 4).
TEST(DaemonChargePump, LostTraceRecordsStopItForGood) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to mount a 256 KiB tmpfs";
  namespace fs = std::filesystem;
  std::string tmpl = (fs::temp_directory_path() / "stepmod-pump-XXXXXX").string();
  ASSERT_NE(::mkdtemp(tmpl.data()), nullptr);
  const std::string dir = tmpl;
  if (::mount("tmpfs", dir.c_str(), "tmpfs", 0, "size=256k") != 0) {
    fs::remove_all(dir);
    GTEST_SKIP() << "cannot mount a tmpfs: " << std::strerror(errno);
  }
  {
    DaemonProcess daemon(config(), DaemonOptions{true, "", dir + "/a.vcd", ""});
    ASSERT_TRUE(daemon.wait_ready()) << daemon.log();
    RawShmPlc plc(daemon.name());
    ipc::SimPanelClient panel(daemon.name());
    const auto wire = [&] { return (panel.read(0).outputs & 16u) != 0; };
    // Running: the wire changes within 100 ms.
    const bool first = wire();
    EXPECT_TRUE(plc.wait([&] { return wire() != first; }, milliseconds(2'000))) << "not running";
    {
      std::ofstream f(dir + "/filler", std::ios::binary);
      const std::string chunk(4096, 'x');
      while (fs::space(dir).available >= chunk.size()) f << chunk << std::flush;
      for (int i = 0; i < 4096 && f; ++i) f << 'x' << std::flush;
    }
    plc.configure();
    plc.command(cmd::kRelativeMove, 5'000, 20'000, 200, 200);  // records the disk has no room for
    ASSERT_TRUE(plc.wait(
        [&] { return (plc.client().read_health().flags & STEPMOD_HEALTH_TRACE_LOST) != 0; },
        milliseconds(5'000)))
        << daemon.log();
    sleep_ns(kReact);
    // Stopped low, for good: no change for many half periods.
    EXPECT_FALSE(wire());
    bool changed = false;
    for (int i = 0; i < 300 && !changed; ++i) {
      changed = wire();
      sleep_ns(kNsPerMs);
    }
    EXPECT_FALSE(changed) << "the wire rose after the trace lost records";
    EXPECT_EQ(daemon.terminate(), 3) << daemon.log();
    EXPECT_NE(daemon.log().find("charge pump stopped (trace records lost)"), std::string::npos)
        << daemon.log();
  }
  ::umount(dir.c_str());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace stepmod::testing

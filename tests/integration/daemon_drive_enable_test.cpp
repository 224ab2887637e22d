// End to end, issue 19: the drive-enable output (an extension) on the simulated machine. The
// panel's output levels show its wire in bit 3. Released until the axis is configured, asserted
// then; a move commanded within enable_delay_us waits for the drive; an E-stop releases it when
// enable_release_on says so. Timing margins are wide (a 2 s delay, checked 300 ms in) so that
// a loaded machine cannot make the test pass or fail by accident.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "ipc/sim_panel.hpp"
#include "tests/support/daemon_process.hpp"
#include "tests/support/shm_plc_3601.hpp"
#include "tests/support/sim_config.hpp"
#include "tests/support/vcd_reader.hpp"

namespace stepmod::testing {
namespace {

namespace m = words::m3601;
namespace cmd = m::cmd_msw;
using std::chrono::milliseconds;

std::string config(
    const std::string& enable_keys =
        "enable = 12\nenable_delay_us = 2000000\nenable_release_on = [\"estop\"]\n") {
  std::string c = sim_3601_config("", "cw_limit_at = 10000000\nccw_limit_at = -10000000\n");
  const std::string anchor = "enc_z = 11\n";
  c.replace(c.find(anchor), anchor.size(), anchor + enable_keys);
  return c;
}

bool enabled(const ipc::SimPanelClient& panel) {
  return (panel.read(0).outputs & 8u) != 0;
}

TEST(DaemonDriveEnable, AssertedOnceConfiguredStepsWaitForTheDelayEStopReleases) {
  DaemonProcess daemon(config(), false);
  ASSERT_TRUE(daemon.wait_ready()) << daemon.log();
  RawShmPlc plc(daemon.name());
  ipc::SimPanelClient panel(daemon.name());
  EXPECT_FALSE(enabled(panel)) << "released until the axis is configured";
  plc.configure();
  ASSERT_TRUE(plc.wait([&] { return enabled(panel); }, milliseconds(2'000))) << daemon.log();

  // A move commanded at once, its command bit held as a PLC holds it until the module acts.
  plc.write(cmd::kRelativeMove, 0, 100, 1'000, 200, 200);
  std::this_thread::sleep_for(milliseconds(300));
  EXPECT_EQ(plc.position(), 0) << "no step before the drive is ready";
  EXPECT_FALSE(plc.moving());
  ASSERT_TRUE(plc.wait([&] { return plc.position() == 100; }, milliseconds(8'000))) << daemon.log();
  plc.write(0, 0, 0, 0, 0, 0);

  panel.force(0, 3, true);  // E-stop (active high as configured)
  ASSERT_TRUE(plc.wait([&] { return !enabled(panel); }, milliseconds(2'000))) << daemon.log();
  panel.force(0, 3, false);
  ASSERT_TRUE(plc.wait([&] { return enabled(panel); }, milliseconds(2'000))) << daemon.log();
  const std::string log = daemon.log();
  EXPECT_NE(log.find("axis 1: drive enabled; commands wait 2000000 us"), std::string::npos) << log;
  EXPECT_NE(log.find("axis 1: drive enable released (E-stop input active)"), std::string::npos)
      << log;
}

// The enable line is a wire of the VCD (axis1.enable), so the delay can be checked from outside,
// by the trace alone: an active-low enable is a high wire at #0 (released), falls when the axis
// is configured, and rises again when the daemon exits; no step edge comes before the fall plus
// enable_delay_us, and every one of the commanded steps comes while the drive is enabled.
TEST(DaemonDriveEnable, VcdShowsTheEnableWireAndNoStepBeforeItsDelay) {
  constexpr std::int64_t kDelayNs = 300'000'000;
  DaemonProcess daemon(
      config("enable = { offset = 12, active_low = true }\n"
             "enable_delay_us = 300000\n"));
  ASSERT_TRUE(daemon.wait_ready()) << daemon.log();
  RawShmPlc plc(daemon.name());
  plc.configure();
  // Commanded at once: the module acts on it only once the drive is ready.
  plc.write(cmd::kRelativeMove, 0, 100, 1'000, 200, 200);
  ASSERT_TRUE(plc.wait([&] { return plc.position() == 100; }, milliseconds(8'000))) << daemon.log();
  plc.write(0, 0, 0, 0, 0, 0);
  ASSERT_EQ(daemon.terminate(), 0) << daemon.log();

  const Vcd vcd = read_vcd(daemon.trace_path());
  ASSERT_EQ(vcd.wires.count("axis1.enable"), 1u) << "no enable wire in the VCD";
  const std::vector<VcdChange>& en = vcd.wires.at("axis1.enable");
  // #0 high (released, active low), a fall (enabled), a rise at exit (released): nothing else.
  ASSERT_EQ(en.size(), 3u) << "changes of axis1.enable";
  EXPECT_EQ(en[0].t, 0);
  EXPECT_EQ(en[0].level, 1) << "active-low enable released at #0: a high wire";
  EXPECT_EQ(en[1].level, 0) << "asserted: a low wire";
  EXPECT_EQ(en[2].level, 1) << "released at daemon exit";
  const std::int64_t enabled_at = en[1].t;
  const std::int64_t released_at = en[2].t;

  const std::vector<std::int64_t> steps = vcd.rising("axis1.step");
  ASSERT_EQ(steps.size(), 100u) << "step pulses in the VCD";
  EXPECT_GE(steps.front(), enabled_at + kDelayNs)
      << "first step " << steps.front() << " ns, enable at " << enabled_at << " ns + delay "
      << kDelayNs << " ns";
  EXPECT_LT(steps.back(), released_at) << "steps while the drive was released";
}

}  // namespace
}  // namespace stepmod::testing

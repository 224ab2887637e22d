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

namespace stepmod::testing {
namespace {

namespace m = words::m3601;
namespace cmd = m::cmd_msw;
using std::chrono::milliseconds;

std::string config() {
  std::string c = sim_3601_config("", "cw_limit_at = 10000000\nccw_limit_at = -10000000\n");
  const std::string anchor = "enc_z = 11\n";
  c.replace(c.find(anchor), anchor.size(),
            anchor + "enable = 12\nenable_delay_us = 2000000\nenable_release_on = [\"estop\"]\n");
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

}  // namespace
}  // namespace stepmod::testing

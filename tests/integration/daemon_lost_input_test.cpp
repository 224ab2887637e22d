// End to end, issue 18 item 5 / issue 19: input events lost (here the simulated machine's event
// FIFO overflowing, as a GPIO line's kernel FIFO does) stop the moving axis with Position
// Invalid, set health bit 5 and are logged. The overflow is made certain, not timing-dependent:
// a FIFO of 2 events and an encoder of 4 counts per step, whose 4 edges of one step are pushed
// by one line write before the control thread can take any.
#include <gtest/gtest.h>

#include <chrono>

#include "tests/support/daemon_process.hpp"
#include "tests/support/shm_plc_3601.hpp"
#include "tests/support/sim_config.hpp"

namespace stepmod::testing {
namespace {

namespace m = words::m3601;
using namespace m::status_msw;
namespace cmd = m::cmd_msw;
using std::chrono::milliseconds;

TEST(DaemonLostInput, SimEventFifoOverflowStopsTheMovingAxisWithPositionInvalid) {
  DaemonProcess daemon(sim_3601_config("", R"(cw_limit_at = 10000000
ccw_limit_at = -10000000
encoder_ratio = 4
event_ring = 2
)"),
                       false);
  ASSERT_TRUE(daemon.wait_ready()) << daemon.log();
  RawShmPlc plc(daemon.name());
  plc.configure();
  plc.command(cmd::kPresetPosition, 0);
  EXPECT_EQ(plc.client().read_health().flags & STEPMOD_HEALTH_INPUT_LOST, 0u);
  // 1,000 steps/s, 100,000 steps: 100 s if nothing stopped it.
  plc.command(cmd::kRelativeMove, 100'000, 1'000, 200, 200);
  ASSERT_TRUE(plc.wait([&] { return plc.position() > 0; }, milliseconds(5'000))) << daemon.log();
  ASSERT_TRUE(plc.wait([&] { return !plc.moving(); }, milliseconds(5'000))) << daemon.log();
  EXPECT_TRUE(plc.status(kStopped));
  EXPECT_TRUE(plc.status(kPositionInvalid));
  EXPECT_FALSE(plc.status(kMoveComplete));
  EXPECT_LT(plc.position(), 100'000);
  ASSERT_TRUE(
      plc.wait([&] { return (plc.client().read_health().flags & STEPMOD_HEALTH_INPUT_LOST) != 0; },
               milliseconds(2'000)));
  const std::string log = daemon.log();
  EXPECT_NE(log.find("input event(s) lost"), std::string::npos) << log;
  EXPECT_NE(log.find("1 moving axis/axes stopped, position invalid"), std::string::npos) << log;
  // The reason names the loss, not a PLC that never left Run mode (3601-PI-07 before).
  EXPECT_NE(log.find("3601-PI-S3: an input edge was lost (stepmod)"), std::string::npos) << log;
  EXPECT_EQ(plc.client().read_reason(0).item, 10693u);
}

}  // namespace
}  // namespace stepmod::testing

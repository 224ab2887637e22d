// The drive-enable outputs' rules (daemon/drive_enable.hpp) on the simulated backend, whose panel
// output levels show the enable line's wire level in bit 3.
#include "daemon/drive_enable.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "gpio/sim_backend.hpp"
#include "config/config.hpp"

namespace stepmod::tools {
namespace {

struct Rig {
  std::vector<gpio::SimAxisSetup> setups;
  std::unique_ptr<gpio::SimBackend> sim;
  std::unique_ptr<DriveEnable> enable;

  explicit Rig(std::uint8_t release, bool active_low = false, Nanos delay = 5 * kNsPerMs) {
    gpio::SimAxisSetup s;
    s.lines.out[0] = 1;
    s.lines.out[1] = 2;
    s.lines.enable = 3;
    s.lines.enable_opt.active_low = active_low;
    s.sim.encoder_ratio = 0;
    gpio::SimAxisSetup plain = s;
    plain.lines.enable.reset();
    setups = {s, plain};
    sim = std::make_unique<gpio::SimBackend>(setups);
    enable = std::make_unique<DriveEnable>(
        *sim, std::vector<DriveEnable::AxisSetup>{{true, delay, release}, {false, 0, release}});
  }
  bool wire(unsigned axis) const {
    return (sim->output_levels(axis) & gpio::SimBackend::kEnableLevelBit) != 0;
  }
};

DriveEnable::Conditions configured() {
  DriveEnable::Conditions c;
  c.configured = true;
  return c;
}

TEST(DriveEnable, ReleasedUntilConfiguredThenAssertedAndHeldForTheDelay) {
  Rig r(0);
  EXPECT_FALSE(r.wire(0));
  r.enable->update(0, DriveEnable::Conditions{}, 1000);
  EXPECT_FALSE(r.wire(0));
  EXPECT_FALSE(r.enable->holding(1000));
  r.enable->update(0, configured(), 2000);
  EXPECT_TRUE(r.wire(0));
  EXPECT_TRUE(r.enable->asserted(0));
  EXPECT_TRUE(r.enable->holding(2000));
  EXPECT_TRUE(r.enable->holding(2000 + 5 * kNsPerMs - 1));
  EXPECT_FALSE(r.enable->holding(2000 + 5 * kNsPerMs));
}

TEST(DriveEnable, ActiveLowEnableIsAHighWireWhenReleased) {
  Rig r(0, true);
  EXPECT_TRUE(r.wire(0));
  r.enable->update(0, configured(), 0);
  EXPECT_FALSE(r.wire(0));
}

TEST(DriveEnable, HoldsThroughFaultsUnlessConfiguredToRelease) {
  Rig hold(0);
  DriveEnable::Conditions c = configured();
  hold.enable->update(0, c, 0);
  c.estop = c.fault = c.plc_lost = c.configuration_mode = true;
  hold.enable->update(0, c, 1);
  EXPECT_TRUE(hold.wire(0)) << "default: holding torque kept on every condition";

  for (std::uint8_t bit :
       {kReleaseOnEStop, kReleaseOnFault, kReleaseOnPlcLoss, kReleaseOnConfigMode}) {
    Rig r(bit);
    DriveEnable::Conditions k = configured();
    r.enable->update(0, k, 0);
    ASSERT_TRUE(r.wire(0));
    k.estop = bit == kReleaseOnEStop;
    k.fault = bit == kReleaseOnFault;
    k.plc_lost = bit == kReleaseOnPlcLoss;
    k.configuration_mode = bit == kReleaseOnConfigMode;
    r.enable->update(0, k, 1);
    EXPECT_FALSE(r.wire(0)) << "release bit " << int(bit);
    r.enable->update(0, configured(), 2);
    EXPECT_TRUE(r.wire(0)) << "asserted again when the condition ends";
    EXPECT_TRUE(r.enable->holding(2)) << "and the delay starts again";
  }
}

TEST(DriveEnable, AnOtherConditionThanTheConfiguredOneKeepsTheDrive) {
  Rig r(kReleaseOnEStop);
  DriveEnable::Conditions c = configured();
  r.enable->update(0, c, 0);
  c.plc_lost = true;
  r.enable->update(0, c, 1);
  EXPECT_TRUE(r.wire(0));
}

TEST(DriveEnable, AnAxisWithoutAnEnableLineIsNeverHeld) {
  Rig r(0);
  r.enable->update(1, configured(), 0);
  EXPECT_FALSE(r.enable->holding(0));
  EXPECT_FALSE(r.wire(1));
  EXPECT_TRUE(r.enable->any_wired());
}

TEST(DriveEnable, IdleOutputsReleaseIt) {
  Rig r(0);
  r.enable->update(0, configured(), 0);
  ASSERT_TRUE(r.wire(0));
  r.sim->idle_outputs();
  EXPECT_FALSE(r.wire(0));
}

}  // namespace
}  // namespace stepmod::tools

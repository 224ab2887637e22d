// The simulated machine honours the line options (issue 19): an input nothing simulated drives
// rests at its pull resistor's level (inverted for the module when active-low), an active-low
// output's wire level is inverted for the panel, and pulled lines do not follow the simulation.
#include <gtest/gtest.h>

#include <vector>

#include "gpio/sim_backend.hpp"

namespace stepmod::gpio {
namespace {

constexpr unsigned kHome = static_cast<unsigned>(InputLine::kHome);
constexpr unsigned kEStop = static_cast<unsigned>(InputLine::kEStop);
constexpr unsigned kCapture = static_cast<unsigned>(InputLine::kCapture);
constexpr unsigned kCwLimit = static_cast<unsigned>(InputLine::kCwLimit);

SimAxisSetup base() {
  SimAxisSetup s;
  s.lines.out[0] = 1;
  s.lines.out[1] = 2;
  s.sim.encoder_ratio = 0;
  return s;
}

TEST(GpioSimLineOptions, UnconnectedInputWithPullUpReadsHigh) {
  SimAxisSetup s = base();
  s.lines.in[kEStop] = 3;
  s.lines.in_opt[kEStop].bias = Bias::kPullUp;
  s.lines.in[kCapture] = 4;  // no bias: rests low as before
  const std::vector<SimAxisSetup> axes = {s};
  SimBackend b(axes);
  EXPECT_TRUE(b.read(0, InputLine::kEStop));
  EXPECT_FALSE(b.read(0, InputLine::kCapture));
}

TEST(GpioSimLineOptions, PullUpOnAnActiveLowInputReadsLogicalLow) {
  SimAxisSetup s = base();
  s.lines.in[kEStop] = 3;
  s.lines.in_opt[kEStop].bias = Bias::kPullUp;
  s.lines.in_opt[kEStop].active_low = true;
  const std::vector<SimAxisSetup> axes = {s};
  SimBackend b(axes);
  EXPECT_FALSE(b.read(0, InputLine::kEStop));
}

TEST(GpioSimLineOptions, PullDownBeatsTheNcRestLevel) {
  SimAxisSetup s = base();
  s.sim.contacts_nc = true;  // an NC machine's undriven inputs rest high...
  s.lines.in[kCapture] = 3;
  s.lines.in_opt[kCapture].bias = Bias::kPullDown;  // ...but this one is pulled down
  const std::vector<SimAxisSetup> axes = {s};
  SimBackend b(axes);
  EXPECT_FALSE(b.read(0, InputLine::kCapture));
}

TEST(GpioSimLineOptions, ASimulatedSwitchIsNotOverriddenByItsBias) {
  SimAxisSetup s = base();
  s.sim.home_from = 2;
  s.sim.home_to = 3;
  s.lines.in[kHome] = 3;
  s.lines.in_opt[kHome].bias = Bias::kPullUp;  // driven by the simulated switch: bias is moot
  const std::vector<SimAxisSetup> axes = {s};
  SimBackend b(axes);
  EXPECT_FALSE(b.read(0, InputLine::kHome));
  b.write(0, OutputLine::kDir, true, 10);
  b.write(0, OutputLine::kStep, true, 20);
  b.write(0, OutputLine::kStep, false, 30);
  b.write(0, OutputLine::kStep, true, 40);
  EXPECT_EQ(b.position(0), 2);
  EXPECT_TRUE(b.read(0, InputLine::kHome));
}

TEST(GpioSimLineOptions, PulledLimitWithoutPositionStaysAtItsPull) {
  SimAxisSetup s = base();
  s.lines.in[kCwLimit] = 3;
  s.lines.in_opt[kCwLimit].bias = Bias::kPullUp;
  const std::vector<SimAxisSetup> axes = {s};
  SimBackend b(axes);
  b.write(0, OutputLine::kDir, true, 10);
  b.write(0, OutputLine::kStep, true, 20);
  EXPECT_TRUE(b.read(0, InputLine::kCwLimit));
  InputEvent ev[4];
  EXPECT_EQ(b.wait_events(ev, 0), 0u) << "a pulled line makes no events";
}

TEST(GpioSimLineOptions, ActiveLowOutputIsInvertedForThePanel) {
  SimAxisSetup s = base();
  s.lines.out_opt[0].active_low = true;  // step
  const std::vector<SimAxisSetup> axes = {s};
  SimBackend b(axes);
  EXPECT_EQ(b.output_levels(0), 1u) << "idle step (logical low) is a high wire";
  b.write(0, OutputLine::kStep, true, 10);
  EXPECT_EQ(b.output_levels(0), 0u);
  EXPECT_EQ(b.position(0), -1) << "the drive still steps on the logical pulse";
  EXPECT_TRUE(b.line_options(0, false, 0).active_low);
  EXPECT_FALSE(b.line_options(0, false, 1).active_low);
}

}  // namespace
}  // namespace stepmod::gpio

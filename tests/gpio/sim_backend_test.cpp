// The sim backend: wiring from the axis config, reads, wait_events, panel accessors.
#include "gpio/sim_backend.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace stepmod::gpio {
namespace {

SimAxisSetup axis(bool with_home) {
  SimAxisSetup s;
  s.lines.out[0] = 17;  // step
  s.lines.out[1] = 27;  // dir
  if (with_home) s.lines.in[static_cast<unsigned>(InputLine::kHome)] = 13;
  s.lines.in[static_cast<unsigned>(InputLine::kEStop)] = 19;
  s.sim.home_from = 1;
  s.sim.home_to = 1;
  s.sim.encoder_ratio = 0;
  return s;
}

TEST(GpioSimBackend, WiringComesFromTheAxisConfig) {
  const std::vector<SimAxisSetup> axes = {axis(true), axis(false)};
  SimBackend b(axes);
  EXPECT_EQ(b.axes(), 2u);
  EXPECT_TRUE(b.has_output(0, OutputLine::kStep));
  EXPECT_TRUE(b.has_output(0, OutputLine::kDir));
  EXPECT_FALSE(b.has_output(0, OutputLine::kGpo));
  EXPECT_TRUE(b.has_input(0, InputLine::kHome));
  EXPECT_FALSE(b.has_input(1, InputLine::kHome));
  EXPECT_TRUE(b.has_input(1, InputLine::kEStop));
  EXPECT_FALSE(b.has_input(0, InputLine::kEncA));
  EXPECT_FALSE(b.has_input(2, InputLine::kEStop)) << "no third axis";
}

TEST(GpioSimBackend, WritesMoveTheRightAxisAndInputsFollow) {
  const std::vector<SimAxisSetup> axes = {axis(true), axis(false)};
  SimBackend b(axes);
  b.write(1, OutputLine::kDir, true, 100);
  b.write(1, OutputLine::kStep, true, 200);
  EXPECT_EQ(b.position(0), 0);
  EXPECT_EQ(b.position(1), 1);
  EXPECT_EQ(b.output_levels(1), 3u);
  EXPECT_EQ(b.output_levels(0), 0u);
  EXPECT_FALSE(b.read(1, InputLine::kHome)) << "axis 2 has no home wired";
  InputEvent ev[4];
  EXPECT_EQ(b.wait_events(ev, 0), 0u);

  b.write(0, OutputLine::kDir, true, 300);
  b.write(0, OutputLine::kStep, true, 400);
  EXPECT_TRUE(b.read(0, InputLine::kHome));
  ASSERT_EQ(b.wait_events(ev, 0), 1u);
  EXPECT_EQ(ev[0].axis, 0);
  EXPECT_EQ(ev[0].line, InputLine::kHome);
  EXPECT_TRUE(ev[0].level);
  EXPECT_EQ(ev[0].t, 400);
  EXPECT_EQ(b.lost_events(), 0u);
}

TEST(GpioSimBackend, UnwiredOutputIsIgnored) {
  const std::vector<SimAxisSetup> axes = {axis(true)};
  SimBackend b(axes);
  b.write(0, OutputLine::kGpo, true, 1);
  EXPECT_EQ(b.output_levels(0), 0u);
}

TEST(GpioSimBackend, WaitEventsTimesOutAtTheDeadline) {
  const std::vector<SimAxisSetup> axes = {axis(true)};
  SimBackend b(axes);
  InputEvent ev[4];
  const Nanos t0 = monotonic_now();
  EXPECT_EQ(b.wait_events(ev, t0 + 3 * kNsPerMs), 0u);
  const Nanos dt = monotonic_now() - t0;
  EXPECT_GE(dt, 3 * kNsPerMs);
  EXPECT_LT(dt, 500 * kNsPerMs);  // generous: the machine is shared
  EXPECT_EQ(b.wait_events(ev, t0), 0u) << "a past deadline returns at once";
}

TEST(GpioSimBackend, WaitEventsDeliversPendingEventsAtOnce) {
  const std::vector<SimAxisSetup> axes = {axis(true), axis(true)};
  SimBackend b(axes);
  for (unsigned a = 0; a < 2; ++a) {
    b.write(a, OutputLine::kDir, true, 10);
    b.write(a, OutputLine::kStep, true, 20 + a);
  }
  std::vector<InputEvent> got;
  InputEvent ev[1];  // one at a time: the second axis must not starve
  const Nanos t0 = monotonic_now();
  while (got.size() < 2 && monotonic_now() - t0 < kNsPerSec) {
    const std::size_t n = b.wait_events(ev, monotonic_now() + 10 * kNsPerMs);
    got.insert(got.end(), ev, ev + n);
  }
  ASSERT_EQ(got.size(), 2u);
  EXPECT_NE(got[0].axis, got[1].axis);
  EXPECT_LT(monotonic_now() - t0, 5 * kNsPerMs * 20);
}

TEST(GpioSimBackend, PanelForceAndRelease) {
  const std::vector<SimAxisSetup> axes = {axis(true)};
  SimBackend b(axes);
  b.force(0, 1u << 3, 1u << 3);  // E-stop forced high
  EXPECT_TRUE(b.read(0, InputLine::kEStop));
  InputEvent ev[4];
  ASSERT_EQ(b.wait_events(ev, 0), 1u);
  EXPECT_EQ(ev[0].line, InputLine::kEStop);
  EXPECT_TRUE(ev[0].level);
  b.force(0, 0, 0);
  ASSERT_EQ(b.wait_events(ev, 0), 1u);
  EXPECT_FALSE(ev[0].level);
  EXPECT_FALSE(b.read(0, InputLine::kEStop));
}

TEST(GpioSimBackend, PulseFormatReachesTheDrive) {
  const std::vector<SimAxisSetup> axes = {axis(false)};
  SimBackend b(axes);
  b.set_pulse_format(0, PulseFormat::kCwCcw);
  b.write(0, OutputLine::kDir, true, 1);
  EXPECT_EQ(b.position(0), -1);
  b.idle_outputs();
  EXPECT_EQ(b.output_levels(0), 0u);
  EXPECT_EQ(b.position(0), -1) << "idling (falling edges) does not move";
}

TEST(GpioSimBackend, EncoderAccessor) {
  SimAxisSetup s = axis(false);
  s.sim.encoder_ratio = 4;
  const std::vector<SimAxisSetup> axes = {s};
  SimBackend b(axes);
  b.write(0, OutputLine::kDir, true, 1);
  b.write(0, OutputLine::kStep, true, 2);
  EXPECT_EQ(b.encoder(0), 4);
}

}  // namespace
}  // namespace stepmod::gpio

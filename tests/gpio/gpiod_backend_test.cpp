// The gpiod backend. Without a GPIO chip (the build machines) only the error paths run; with a
// gpio-sim chip (the test VM) set
//   STEPMOD_TEST_GPIOSIM_CHIP  chip name, e.g. gpiochip1
//   STEPMOD_TEST_GPIOSIM_SYSFS its sysfs directory, e.g. /sys/devices/platform/gpio-sim.0/gpiochip1
// (a bank of at least 8 free lines, pulled down) and the real-chip tests run too: the VM case
// vm_cases/gpio_backend.sh does that with the `test_gpiod_backend` program.
#include "gpio/gpiod_backend.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace stepmod::gpio {
namespace {

AxisLines lines(unsigned step, unsigned dir) {
  AxisLines l;
  l.out[0] = step;
  l.out[1] = dir;
  return l;
}

std::string error_of(const std::string& chip, const std::vector<AxisLines>& axes) {
  try {
    GpiodBackend b(chip, axes);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(GpioGpiodBackend, MissingChipIsAnErrorNamingIt) {
  const std::vector<AxisLines> axes = {lines(17, 27)};
  const std::string msg = error_of("gpiochip-stepmod-missing", axes);
  EXPECT_NE(msg.find("gpiochip-stepmod-missing"), std::string::npos) << msg;
  const std::string msg2 = error_of("/dev/gpiochip-stepmod-missing", axes);
  EXPECT_NE(msg2.find("/dev/gpiochip-stepmod-missing"), std::string::npos) << msg2;
}

// ---- real chip (gpio-sim) ---------------------------------------------------------------------

struct GpioSim {
  std::string chip, sysfs;
  static GpioSim get() {
    const char* c = std::getenv("STEPMOD_TEST_GPIOSIM_CHIP");
    const char* s = std::getenv("STEPMOD_TEST_GPIOSIM_SYSFS");
    return {c ? c : "", s ? s : ""};
  }
  bool ok() const { return !chip.empty() && !sysfs.empty(); }
  // gpio-sim: sim_gpio<N>/value is the level the line is driven to (outputs); writing
  // "pull-up"/"pull-down" to sim_gpio<N>/pull drives an input from outside.
  int value(unsigned off) const {
    std::ifstream f(sysfs + "/sim_gpio" + std::to_string(off) + "/value");
    int v = -1;
    f >> v;
    return v;
  }
  void pull(unsigned off, bool up) const {
    std::ofstream f(sysfs + "/sim_gpio" + std::to_string(off) + "/pull");
    f << (up ? "pull-up" : "pull-down");
  }
};

#define REQUIRE_GPIOSIM(sim)          \
  const GpioSim sim = GpioSim::get(); \
  if (!sim.ok()) GTEST_SKIP() << "no gpio-sim chip (STEPMOD_TEST_GPIOSIM_CHIP/SYSFS)"

TEST(GpioGpiodBackend, SimChipOutputsStartLowAndFollowWrites) {
  REQUIRE_GPIOSIM(sim);
  AxisLines a = lines(0, 1);
  a.out[2] = 2;
  const std::vector<AxisLines> axes = {a, lines(3, 4)};
  GpiodBackend b(sim.chip, axes);
  for (unsigned o = 0; o < 5; ++o) EXPECT_EQ(sim.value(o), 0) << o;
  b.write(0, OutputLine::kDir, true, 0);
  b.write(1, OutputLine::kStep, true, 0);
  EXPECT_EQ(sim.value(1), 1);
  EXPECT_EQ(sim.value(3), 1);
  EXPECT_EQ(sim.value(0), 0);
  b.write(0, OutputLine::kDir, false, 0);
  EXPECT_EQ(sim.value(1), 0);
  EXPECT_EQ(sim.value(3), 1) << "the other lines of the bulk keep their levels";
  b.idle_outputs();
  EXPECT_EQ(sim.value(3), 0);
  EXPECT_EQ(b.write_errors(), 0u);
}

TEST(GpioGpiodBackend, SimChipInputEdgesWithMonotonicTimestamps) {
  REQUIRE_GPIOSIM(sim);
  AxisLines a = lines(0, 1);
  a.in[static_cast<unsigned>(InputLine::kHome)] = 5;
  a.in[static_cast<unsigned>(InputLine::kCwLimit)] = 6;
  const std::vector<AxisLines> axes = {a};
  sim.pull(5, false);
  sim.pull(6, false);
  GpiodBackend b(sim.chip, axes);
  EXPECT_FALSE(b.read(0, InputLine::kHome));
  InputEvent ev[8];
  EXPECT_EQ(b.wait_events(ev, monotonic_now() + 2 * kNsPerMs), 0u) << "timeout";

  const Nanos t0 = monotonic_now();
  sim.pull(5, true);
  std::size_t n = b.wait_events(ev, monotonic_now() + kNsPerSec);
  const Nanos t1 = monotonic_now();
  ASSERT_EQ(n, 1u);
  EXPECT_EQ(ev[0].axis, 0);
  EXPECT_EQ(ev[0].line, InputLine::kHome);
  EXPECT_TRUE(ev[0].level);
  EXPECT_GE(ev[0].t, t0) << "kernel timestamp is CLOCK_MONOTONIC";
  EXPECT_LE(ev[0].t, t1);
  EXPECT_TRUE(b.read(0, InputLine::kHome));

  sim.pull(6, true);
  sim.pull(6, false);
  std::vector<InputEvent> got;
  const Nanos deadline = monotonic_now() + kNsPerSec;
  while (got.size() < 2 && monotonic_now() < deadline) {
    n = b.wait_events(ev, deadline);
    got.insert(got.end(), ev, ev + n);
  }
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0].line, InputLine::kCwLimit);
  EXPECT_TRUE(got[0].level);
  EXPECT_FALSE(got[1].level);
  EXPECT_LE(got[0].t, got[1].t);
  EXPECT_EQ(b.lost_events(), 0u);
}

TEST(GpioGpiodBackend, SimChipOffsetOutOfRangeNamesTheLine) {
  REQUIRE_GPIOSIM(sim);
  const std::vector<AxisLines> axes = {lines(0, 9999)};
  const std::string msg = error_of(sim.chip, axes);
  EXPECT_NE(msg.find(sim.chip), std::string::npos) << msg;
  EXPECT_NE(msg.find("9999"), std::string::npos) << msg;
  EXPECT_NE(msg.find("axis1.dir"), std::string::npos) << msg;
  EXPECT_NE(msg.find("out of range"), std::string::npos) << msg;
}

TEST(GpioGpiodBackend, SimChipBusyLineNamesTheLine) {
  REQUIRE_GPIOSIM(sim);
  const std::vector<AxisLines> first = {lines(0, 1)};
  GpiodBackend holder(sim.chip, first);
  const std::vector<AxisLines> second = {lines(2, 1)};
  const std::string msg = error_of(sim.chip, second);
  EXPECT_NE(msg.find("busy"), std::string::npos) << msg;
  EXPECT_NE(msg.find("axis1.dir"), std::string::npos) << msg;
  EXPECT_NE(msg.find("line 1"), std::string::npos) << msg;
}

TEST(GpioGpiodBackend, SimChipOffsetUsedTwiceNamesBothKeys) {
  REQUIRE_GPIOSIM(sim);
  AxisLines a = lines(0, 1);
  a.in[static_cast<unsigned>(InputLine::kHome)] = 0;
  const std::vector<AxisLines> axes = {a};
  const std::string msg = error_of(sim.chip, axes);
  EXPECT_NE(msg.find("axis1.home"), std::string::npos) << msg;
  EXPECT_NE(msg.find("axis1.step"), std::string::npos) << msg;
}

// The control thread's outputs: the drive enable and the module's charge pump (carried by its
// first axis' lines), each written alone; idle is inactive, so an active-low pump is a high wire.
TEST(GpioGpiodBackend, SimChipChargePumpAndEnableFollowTheControlThread) {
  REQUIRE_GPIOSIM(sim);
  AxisLines a = lines(0, 1);
  a.enable = 2;
  a.charge_pump = 3;
  a.charge_pump_opt.active_low = true;
  {  // the backend releases its lines before the second request below
    const std::vector<AxisLines> axes = {a};
    GpiodBackend b(sim.chip, axes);
    EXPECT_EQ(sim.value(3), 1) << "inactive, active low: a high wire";
    b.set_charge_pump(0, true);
    EXPECT_EQ(sim.value(3), 0);
    EXPECT_EQ(sim.value(2), 0) << "the enable keeps its level";
    b.set_enable(0, true);
    b.set_charge_pump(0, false);
    EXPECT_EQ(sim.value(2), 1);
    EXPECT_EQ(sim.value(3), 1);
    b.set_charge_pump(0, true);
    b.idle_outputs();
    EXPECT_EQ(sim.value(3), 1) << "idle: inactive";
    EXPECT_EQ(b.write_errors(), 0u);
  }
  AxisLines twice = lines(0, 1);
  twice.charge_pump = 1;
  const std::string msg = error_of(sim.chip, {twice});
  EXPECT_NE(msg.find("charge_pump.line"), std::string::npos) << msg;
}

TEST(GpioGpiodBackend, SimChipReleasesLinesOnDestruction) {
  REQUIRE_GPIOSIM(sim);
  AxisLines a = lines(0, 1);
  a.in[static_cast<unsigned>(InputLine::kHome)] = 5;
  const std::vector<AxisLines> axes = {a};
  { GpiodBackend b(sim.chip, axes); }
  GpiodBackend again(sim.chip, axes);  // would be EBUSY if anything leaked
  EXPECT_EQ(again.axes(), 1u);
}

}  // namespace
}  // namespace stepmod::gpio

// The configuration file (docs/interface.md 2): defaults, a full valid file, and one test per error
// (the message names the file, the key and the line).
#include "config/config.hpp"

#include <unistd.h>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

namespace stepmod::tools {
namespace {

constexpr const char* kMinimal3601 = R"(
[module]
type = "3601"

[[axis]]
step = 17
dir = 27
)";

constexpr const char* kFull3601 = R"([module]
type = "3601"
name = "press-1"
scan_us = 2000
plc_timeout_ms = 500

[gpio]
backend = "gpiod"
chip = "/dev/gpiochip1"

[rt]
priority = 70
cpu = 1
late_limit_us = 250

[[axis]]
step = 17
dir = 27
capture = 5
external = 6
home = 13
estop = 19
cw_limit = 26
ccw_limit = 21
enc_a = 20
enc_b = 16
enc_z = 12
step_pulse_ns = 2500
dir_setup_ns = 6000

[axis.sim]
start_position = -5
cw_limit_at = 100000
ccw_limit_at = -100000
home_from = 5000
home_to = 5100
contacts = "NC"
encoder_ratio = -4.0
marker_every = 4000
)";

// The whole message, for a config that must be rejected.
std::string error_of(const std::string& text) {
  try {
    parse_config(text, "test.toml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(accepted)";
}

#define EXPECT_CONFIG_ERROR(text, expected) EXPECT_EQ(error_of(text), expected)

TEST(Config, MinimalFileGetsEveryDefault) {
  const Config c = parse_config(kMinimal3601, "m.toml");
  EXPECT_EQ(c.file, "m.toml");
  EXPECT_EQ(c.type, ModuleType::k3601);
  EXPECT_EQ(c.name, "stepmod");
  EXPECT_EQ(c.scan_ns, 1'000'000);
  EXPECT_EQ(c.plc_timeout_ns, 0);
  EXPECT_EQ(c.backend, Config::Backend::kSim);
  EXPECT_EQ(c.chip, "gpiochip0");
  EXPECT_EQ(c.rt_priority, 80);
  EXPECT_EQ(c.rt_cpu, -1);
  // [rt] late_limit_us = 200000 (issue 18: the longest pause at any speed; before: 1000)
  EXPECT_EQ(c.late_limit_ns, 200'000'000);
  ASSERT_EQ(c.axes.size(), 1u);
  const AxisSection& a = c.axes[0];
  EXPECT_EQ(a.out[0], 17u);
  EXPECT_EQ(a.out[1], 27u);
  EXPECT_FALSE(a.out[2].has_value());
  for (const auto& in : a.in) EXPECT_FALSE(in.has_value());
  EXPECT_EQ(a.step_pulse_ns, 2'000);
  EXPECT_EQ(a.dir_setup_ns, 5'000);
  EXPECT_EQ(a.lag_limit_steps, 8u);  // [axis] lag_limit_steps (issue 18)
  EXPECT_EQ(a.sim.start_position, 0);
  EXPECT_FALSE(a.sim.cw_limit_at.has_value());
  EXPECT_FALSE(a.sim.ccw_limit_at.has_value());
  EXPECT_FALSE(a.sim.home_from.has_value());
  EXPECT_FALSE(a.sim.home_to.has_value());
  EXPECT_FALSE(a.sim.contacts_nc);
  EXPECT_EQ(a.sim.encoder_ratio, 1.0);
  EXPECT_FALSE(a.sim.marker_every.has_value());
}

TEST(Config, FullValid3601File) {
  const Config c = parse_config(kFull3601, "full.toml");
  EXPECT_EQ(c.name, "press-1");
  EXPECT_EQ(c.scan_ns, 2'000'000);
  EXPECT_EQ(c.plc_timeout_ns, 500'000'000);
  EXPECT_EQ(c.backend, Config::Backend::kGpiod);
  EXPECT_EQ(c.chip, "/dev/gpiochip1");
  EXPECT_EQ(c.rt_priority, 70);
  EXPECT_EQ(c.rt_cpu, 1);
  EXPECT_EQ(c.late_limit_ns, 250'000);
  const AxisSection& a = c.axes.at(0);
  const unsigned want_in[] = {5, 6, 13, 19, 26, 21, 20, 16, 12};
  for (unsigned i = 0; i < kInputLinesPerAxis; ++i) EXPECT_EQ(a.in[i], want_in[i]) << i;
  EXPECT_EQ(a.step_pulse_ns, 2'500);
  EXPECT_EQ(a.dir_setup_ns, 6'000);
  EXPECT_EQ(a.sim.start_position, -5);
  EXPECT_EQ(a.sim.cw_limit_at, 100'000);
  EXPECT_EQ(a.sim.ccw_limit_at, -100'000);
  EXPECT_EQ(a.sim.home_from, 5'000);
  EXPECT_EQ(a.sim.home_to, 5'100);
  EXPECT_TRUE(a.sim.contacts_nc);
  EXPECT_EQ(a.sim.encoder_ratio, -4.0);
  EXPECT_EQ(a.sim.marker_every, 4'000);
}

TEST(Config, Valid3602And3202TwoAxes) {
  const Config c2 = parse_config(R"([module]
type = "3602"
[[axis]]
step = 1
dir = 2
gpo = 3
cw_limit = 4
[[axis]]
step = 5
dir = 6
gpo = 7
)",
                                 "x.toml");
  EXPECT_EQ(c2.type, ModuleType::k3602);
  ASSERT_EQ(c2.axes.size(), 2u);
  EXPECT_EQ(c2.axes[1].out[2], 7u);
  const Config c3 = parse_config(R"([module]
type = "3202"
[[axis]]
step = 1
dir = 2
estop = 3
[[axis]]
step = 5
dir = 6
enc_a = 7
enc_b = 8
)",
                                 "x.toml");
  EXPECT_EQ(c3.type, ModuleType::k3202);
  EXPECT_EQ(c3.axes[1].in[6], 7u);
}

TEST(Config, LoadConfigReadsFileAndNamesIt) {
  const std::string path = "/tmp/stepmod-config-test-" + std::to_string(::getpid()) + ".toml";
  { std::ofstream(path) << kMinimal3601 << "[rt]\npriority = 0\n"; }
  try {
    load_config(path);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), path + ":9: key 'rt.priority': must be an integer 1..99");
  }
  ::unlink(path.c_str());
  try {
    load_config(path);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ": cannot read", 0), 0u) << e.what();
  }
}

TEST(ConfigError, SyntaxErrorHasLine) {
  const std::string e = error_of("[module]\ntype = \"3601\nname = 1\n");
  EXPECT_EQ(e.rfind("test.toml:2: TOML syntax error", 0), 0u) << e;
}

TEST(ConfigError, ModuleTypeRequired) {
  EXPECT_CONFIG_ERROR("[module]\nname = \"x\"\n",
                      "test.toml:1: key 'module.type': required: \"3601\", \"3602\" or \"3202\"");
  EXPECT_CONFIG_ERROR("[[axis]]\nstep = 1\ndir = 2\n",
                      "test.toml: key 'module.type': required: \"3601\", \"3602\" or \"3202\"");
}

TEST(ConfigError, ModuleTypeInvalid) {
  EXPECT_CONFIG_ERROR("[module]\ntype = \"3603\"\n",
                      "test.toml:2: key 'module.type': must be \"3601\", \"3602\" or \"3202\"");
}

TEST(ConfigError, ModuleTypeMustBeQuoted) {
  EXPECT_CONFIG_ERROR(
      "[module]\ntype = 3602\n",
      "test.toml:2: key 'module.type': must be a string in quotes: type = \"3602\"");
  EXPECT_CONFIG_ERROR(
      "[module]\ntype = 3601\n[[axis]]\nstep = 1\ndir = 2\n",
      "test.toml:2: key 'module.type': must be a string in quotes: type = \"3601\"");
}

TEST(ConfigError, UnknownKeysAreErrors) {
  EXPECT_CONFIG_ERROR(
      "[module]\ntype = \"3601\"\nscan_usec = 500\n",
      "test.toml:3: key 'module.scan_usec': unknown key (expected one of: type, name, scan_us, "
      "plc_timeout_ms)");
  const std::string top = error_of(std::string(kMinimal3601) + "[modul]\nx = 1\n");
  EXPECT_EQ(top.rfind("test.toml:8: key 'modul': unknown key", 0), 0u) << top;
  const std::string ax =
      error_of("[module]\ntype = \"3601\"\n[[axis]]\nstep = 1\ndir = 2\nhom = 3\n");
  EXPECT_EQ(ax.rfind("test.toml:6: key 'axis[1].hom': unknown key", 0), 0u) << ax;
  const std::string sim = error_of(std::string(kMinimal3601) + "[axis.sim]\nhome_form = 3\n");
  EXPECT_EQ(sim.rfind("test.toml:9: key 'axis[1].sim.home_form': unknown key", 0), 0u) << sim;
}

TEST(ConfigError, NameCharset) {
  EXPECT_CONFIG_ERROR("[module]\ntype = \"3601\"\nname = \"Press 1\"\n",
                      "test.toml:3: key 'module.name': must be 1..64 characters of a-z, 0-9, '-' "
                      "and '_' (it names /dev/shm/stepmod.NAME)");
  EXPECT_NE(error_of("[module]\ntype = \"3601\"\nname = \"\"\n"), "(accepted)");
  EXPECT_NE(error_of("[module]\ntype = \"3601\"\nname = \"a/b\"\n"), "(accepted)");
}

TEST(ConfigError, ScanUsRange) {
  EXPECT_CONFIG_ERROR("[module]\ntype = \"3601\"\nscan_us = 249\n",
                      "test.toml:3: key 'module.scan_us': must be an integer 250..100000");
  EXPECT_CONFIG_ERROR("[module]\ntype = \"3601\"\nscan_us = 100001\n",
                      "test.toml:3: key 'module.scan_us': must be an integer 250..100000");
  EXPECT_CONFIG_ERROR("[module]\ntype = \"3601\"\nscan_us = 1000.0\n",
                      "test.toml:3: key 'module.scan_us': must be an integer 250..100000");
  EXPECT_EQ(parse_config(std::string(kMinimal3601) + "", "t").scan_ns, 1'000'000);
}

TEST(ConfigError, ScanUsEdgesAccepted) {
  for (int us : {250, 100000}) {
    const std::string t = "[module]\ntype = \"3601\"\nscan_us = " + std::to_string(us) +
                          "\n[[axis]]\nstep = 1\ndir = 2\n";
    EXPECT_EQ(parse_config(t, "t").scan_ns, us * 1000);
  }
}

TEST(ConfigError, PlcTimeoutNonNegative) {
  EXPECT_CONFIG_ERROR("[module]\ntype = \"3601\"\nplc_timeout_ms = -1\n",
                      "test.toml:3: key 'module.plc_timeout_ms': must be an integer 0..3600000");
}

TEST(ConfigError, Backend) {
  EXPECT_CONFIG_ERROR(std::string(kMinimal3601) + "[gpio]\nbackend = \"gpio\"\n",
                      "test.toml:9: key 'gpio.backend': must be one of \"sim\", \"gpiod\"");
  EXPECT_CONFIG_ERROR(
      std::string(kMinimal3601) + "[gpio]\nchip = \"\"\n",
      "test.toml:9: key 'gpio.chip': must be a chip name (gpiochip0), a /dev path or a label");
}

TEST(ConfigError, PriorityAndCpu) {
  EXPECT_CONFIG_ERROR(std::string(kMinimal3601) + "[rt]\npriority = 100\n",
                      "test.toml:9: key 'rt.priority': must be an integer 1..99");
  EXPECT_CONFIG_ERROR(std::string(kMinimal3601) + "[rt]\ncpu = -2\n",
                      "test.toml:9: key 'rt.cpu': must be an integer -1..1023");
  EXPECT_CONFIG_ERROR(std::string(kMinimal3601) + "[rt]\nlate_limit_us = 10\n",
                      "test.toml:9: key 'rt.late_limit_us': must be an integer 20..1000000");
  EXPECT_CONFIG_ERROR(std::string(kMinimal3601) + "lag_limit_steps = 0\n",
                      "test.toml:8: key 'axis[1].lag_limit_steps': must be an integer 1..1000000");
  EXPECT_CONFIG_ERROR(std::string(kMinimal3601) + "[rt]\nlate_limit_us = 0\n",
                      "test.toml:9: key 'rt.late_limit_us': must be an integer 20..1000000");
}

TEST(ConfigError, AxisCountMustMatchModule) {
  EXPECT_CONFIG_ERROR("[module]\ntype = \"3601\"\n",
                      "test.toml:1: key 'axis': module type 3601 needs exactly 1 [[axis]] table, "
                      "found 0");
  EXPECT_CONFIG_ERROR(
      "[module]\ntype = \"3602\"\n[[axis]]\nstep = 1\ndir = 2\n",
      "test.toml:3: key 'axis': module type 3602 needs exactly 2 [[axis]] tables, found 1");
  EXPECT_CONFIG_ERROR(
      std::string(kMinimal3601) + "[[axis]]\nstep = 3\ndir = 4\n",
      "test.toml:8: key 'axis': module type 3601 needs exactly 1 [[axis]] table, found 2");
}

TEST(ConfigError, StepAndDirRequired) {
  EXPECT_CONFIG_ERROR(
      "[module]\ntype = \"3601\"\n[[axis]]\ndir = 2\n",
      "test.toml:3: key 'axis[1].step': required: the line offset of the step (or CW pulse) "
      "output");
  EXPECT_CONFIG_ERROR(
      "[module]\ntype = \"3202\"\n[[axis]]\nstep = 1\ndir = 2\n[[axis]]\nstep = 3\n",
      "test.toml:6: key 'axis[2].dir': required: the line offset of the direction (or CCW "
      "pulse) output");
}

TEST(ConfigError, LineOffsetsNonNegative) {
  EXPECT_CONFIG_ERROR("[module]\ntype = \"3601\"\n[[axis]]\nstep = -1\ndir = 2\n",
                      "test.toml:4: key 'axis[1].step': must be an integer 0..4095");
  EXPECT_CONFIG_ERROR("[module]\ntype = \"3601\"\n[[axis]]\nstep = 1\ndir = 2\nhome = \"13\"\n",
                      "test.toml:6: key 'axis[1].home': must be an integer 0..4095");
}

TEST(ConfigError, LineOffsetsUniqueAcrossAxes) {
  EXPECT_CONFIG_ERROR("[module]\ntype = \"3601\"\n[[axis]]\nstep = 1\ndir = 1\n",
                      "test.toml:5: key 'axis[1].dir': line offset 1 is already used by "
                      "'axis[1].step'");
  EXPECT_CONFIG_ERROR(
      "[module]\ntype = \"3202\"\n[[axis]]\nstep = 1\ndir = 2\nhome = 9\n[[axis]]\nstep = "
      "3\ndir = 4\nhome = 9\n",
      "test.toml:10: key 'axis[2].home': line offset 9 is already used by 'axis[1].home'");
}

TEST(ConfigError, EStopAndEncoderNotOn3602) {
  const std::string head = "[module]\ntype = \"3602\"\n[[axis]]\nstep = 1\ndir = 2\n";
  const std::string tail = "[[axis]]\nstep = 3\ndir = 4\n";
  EXPECT_EQ(error_of(head + "estop = 5\n" + tail)
                .rfind("test.toml:6: key 'axis[1].estop': the "
                       "3602 has no E-stop input",
                       0),
            0u);
  EXPECT_CONFIG_ERROR(head + "enc_z = 5\n" + tail,
                      "test.toml:6: key 'axis[1].enc_z': the 3602 has no encoder input");
}

TEST(ConfigError, SimulatedEncoderNotOn3602) {
  const std::string head = "[module]\ntype = \"3602\"\n[[axis]]\nstep = 1\ndir = 2\n";
  const std::string tail = "[[axis]]\nstep = 3\ndir = 4\n";
  EXPECT_CONFIG_ERROR(head + tail + "[axis.sim]\nencoder_ratio = 2.0\n",
                      "test.toml:10: key 'axis[2].sim.encoder_ratio': the 3602 has no encoder "
                      "input: remove this key");
  EXPECT_CONFIG_ERROR(head + "[axis.sim]\nmarker_every = 100\n" + tail,
                      "test.toml:7: key 'axis[1].sim.marker_every': the 3602 has no encoder "
                      "input: remove this key");
}

TEST(ConfigError, GpoOnlyOn3602) {
  EXPECT_CONFIG_ERROR("[module]\ntype = \"3601\"\n[[axis]]\nstep = 1\ndir = 2\ngpo = 3\n",
                      "test.toml:6: key 'axis[1].gpo': only the 3602 has a general-purpose output");
}

TEST(ConfigError, EncoderPhasesTogether) {
  EXPECT_CONFIG_ERROR(
      "[module]\ntype = \"3601\"\n[[axis]]\nstep = 1\ndir = 2\nenc_b = 3\n",
      "test.toml:6: key 'axis[1].enc_b': enc_a and enc_b must both be given (quadrature needs "
      "both phases)");
}

TEST(ConfigError, PulseTimingBounds) {
  const std::string head = "[module]\ntype = \"3601\"\n[[axis]]\nstep = 1\ndir = 2\n";
  EXPECT_CONFIG_ERROR(head + "step_pulse_ns = 0\n",
                      "test.toml:6: key 'axis[1].step_pulse_ns': must be an integer 100..1000000");
  EXPECT_CONFIG_ERROR(head + "dir_setup_ns = 0\n",
                      "test.toml:6: key 'axis[1].dir_setup_ns': must be an integer 1..1000000");
  EXPECT_CONFIG_ERROR(head + "dir_setup_ns = 1000001\n",
                      "test.toml:6: key 'axis[1].dir_setup_ns': must be an integer 1..1000000");
}

TEST(ConfigError, SimContacts) {
  EXPECT_CONFIG_ERROR(std::string(kMinimal3601) + "[axis.sim]\ncontacts = \"no\"\n",
                      "test.toml:9: key 'axis[1].sim.contacts': must be one of \"NO\", \"NC\"");
}

TEST(ConfigError, SimHomeBothOrNeitherAndOrdered) {
  EXPECT_CONFIG_ERROR(std::string(kMinimal3601) + "[axis.sim]\nhome_from = 5\n",
                      "test.toml:9: key 'axis[1].sim.home_from': home_from and home_to must be "
                      "given together");
  EXPECT_CONFIG_ERROR(std::string(kMinimal3601) + "[axis.sim]\nhome_from = 5\nhome_to = 4\n",
                      "test.toml:10: key 'axis[1].sim.home_to': must be >= home_from (5)");
  EXPECT_EQ(
      parse_config(std::string(kMinimal3601) + "[axis.sim]\nhome_from = 5\nhome_to = 5\n", "t")
          .axes[0]
          .sim.home_to,
      5);
}

TEST(ConfigError, SimLimitsOrdered) {
  EXPECT_CONFIG_ERROR(
      std::string(kMinimal3601) + "[axis.sim]\ncw_limit_at = 10\nccw_limit_at = 10\n",
      "test.toml:10: key 'axis[1].sim.ccw_limit_at': must be less than cw_limit_at (10)");
}

TEST(ConfigError, SimMarkerEveryPositive) {
  EXPECT_CONFIG_ERROR(std::string(kMinimal3601) + "[axis.sim]\nmarker_every = 0\n",
                      "test.toml:9: key 'axis[1].sim.marker_every': must be an integer >= 1");
}

TEST(ConfigError, SimEncoderRatioFinite) {
  const std::string msg =
      "test.toml:9: key 'axis[1].sim.encoder_ratio': must be a finite number, -1000 .. 1000";
  EXPECT_CONFIG_ERROR(std::string(kMinimal3601) + "[axis.sim]\nencoder_ratio = inf\n", msg);
  EXPECT_CONFIG_ERROR(std::string(kMinimal3601) + "[axis.sim]\nencoder_ratio = nan\n", msg);
  // Each step emits |ratio| counts from the pulse thread: a huge ratio would stall it.
  EXPECT_CONFIG_ERROR(std::string(kMinimal3601) + "[axis.sim]\nencoder_ratio = 1e12\n", msg);
  EXPECT_CONFIG_ERROR(std::string(kMinimal3601) + "[axis.sim]\nencoder_ratio = -1001\n", msg);
  EXPECT_EQ(parse_config(std::string(kMinimal3601) + "[axis.sim]\nencoder_ratio = -1000\n", "t")
                .axes[0]
                .sim.encoder_ratio,
            -1000.0);
  EXPECT_EQ(parse_config(std::string(kMinimal3601) + "[axis.sim]\nencoder_ratio = 2\n", "t")
                .axes[0]
                .sim.encoder_ratio,
            2.0);
}

TEST(ConfigError, SimPositionsBounded) {
  // Beyond +-10^12 steps the step count could overflow and position * ratio lose exactness.
  EXPECT_CONFIG_ERROR(
      std::string(kMinimal3601) + "[axis.sim]\nstart_position = 9223372036854775807\n",
      "test.toml:9: key 'axis[1].sim.start_position': must be an integer "
      "-1000000000000..1000000000000");
  EXPECT_CONFIG_ERROR(std::string(kMinimal3601) + "[axis.sim]\ncw_limit_at = 1000000000001\n",
                      "test.toml:9: key 'axis[1].sim.cw_limit_at': must be an integer "
                      "-1000000000000..1000000000000");
  EXPECT_EQ(parse_config(std::string(kMinimal3601) + "[axis.sim]\nhome_from = -1000000000000\n"
                                                     "home_to = 1000000000000\n",
                         "t")
                .axes[0]
                .sim.home_to,
            1'000'000'000'000);
}

TEST(ConfigError, TablesMustBeTables) {
  EXPECT_CONFIG_ERROR("module = 3\n", "test.toml:1: key 'module': must be a table [module]");
  EXPECT_CONFIG_ERROR("[module]\ntype = \"3601\"\n[axis]\nstep = 1\n",
                      "test.toml:3: key 'axis': must be [[axis]] tables");
}

}  // namespace
}  // namespace stepmod::tools

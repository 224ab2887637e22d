// Line keys with electrical options (issue 19): `home = 5` or
// `home = { offset = 5, bias = "pull-up", active_low = true, debounce_us = 2000 }`, and the
// file:line:key errors of options a line or this build's libgpiod cannot take; the charge pump's
// line and frequency.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "config/config.hpp"
#include "config/rack_config.hpp"

namespace stepmod::tools {
namespace {

std::string axis_file(const std::string& backend, const std::string& lines) {
  return "[module]\ntype = \"3601\"\n[gpio]\nbackend = \"" + backend + "\"\n[[axis]]\n" + lines;
}

std::string error_of(const std::string& text) {
  try {
    parse_config(text, "test.toml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(ConfigLines, PlainOffsetsKeepDefaultOptions) {
  const Config c = parse_config(axis_file("gpiod", "step = 17\ndir = 27\nhome = 5\n"), "t");
  const auto& a = c.axes[0];
  EXPECT_EQ(a.out[0], 17u);
  EXPECT_EQ(a.in[static_cast<unsigned>(InputLine::kHome)], 5u);
  const gpio::LineOptions& h = a.in_opt[static_cast<unsigned>(InputLine::kHome)];
  EXPECT_EQ(h.bias, gpio::Bias::kAsIs);
  EXPECT_FALSE(h.active_low);
  EXPECT_EQ(h.debounce_us, 0u);
  EXPECT_EQ(a.out_opt[0].drive, gpio::Drive::kPushPull);
}

TEST(ConfigLines, TablesCarryTheOptions) {
  const Config c =
      parse_config(axis_file("sim",
                             "step = { offset = 17, active_low = true, drive = \"open-drain\" }\n"
                             "dir = { offset = 27, drive = \"open-source\" }\n"
                             "home = { offset = 5, bias = \"pull-up\", active_low = true }\n"
                             "cw_limit = { offset = 6, bias = \"pull-down\", debounce_us = 2000 }\n"
                             "ccw_limit = { offset = 7, bias = \"disabled\" }\n"),
                   "t");
  const auto& a = c.axes[0];
  EXPECT_EQ(a.out[0], 17u);
  EXPECT_TRUE(a.out_opt[0].active_low);
  EXPECT_EQ(a.out_opt[0].drive, gpio::Drive::kOpenDrain);
  EXPECT_EQ(a.out_opt[1].drive, gpio::Drive::kOpenSource);
  const auto in = [&](InputLine l) { return a.in_opt[static_cast<unsigned>(l)]; };
  EXPECT_EQ(a.in[static_cast<unsigned>(InputLine::kHome)], 5u);
  EXPECT_EQ(in(InputLine::kHome).bias, gpio::Bias::kPullUp);
  EXPECT_TRUE(in(InputLine::kHome).active_low);
  EXPECT_EQ(in(InputLine::kCwLimit).bias, gpio::Bias::kPullDown);
  EXPECT_EQ(in(InputLine::kCwLimit).debounce_us, 2000u);
  EXPECT_EQ(in(InputLine::kCcwLimit).bias, gpio::Bias::kDisabled);
}

TEST(ConfigLines, OutputOptionsOnAnInputAndBackAreErrors) {
  EXPECT_EQ(error_of(axis_file(
                "sim", "step = 1\ndir = 2\nhome = { offset = 5, drive = \"open-drain\" }\n")),
            "test.toml:8: key 'axis[1].home.drive': unknown key (expected one of: offset, "
            "active_low, bias, debounce_us)");
  EXPECT_EQ(error_of(axis_file("sim", "step = { offset = 1, bias = \"pull-up\" }\ndir = 2\n")),
            "test.toml:6: key 'axis[1].step.bias': unknown key (expected one of: offset, "
            "active_low, drive)");
}

TEST(ConfigLines, BadValuesNameTheKey) {
  const std::string bias =
      error_of(axis_file("sim", "step = 1\ndir = 2\nhome = { offset = 5, bias = \"up\" }\n"));
  EXPECT_EQ(bias.rfind("test.toml:8: key 'axis[1].home.bias': must be", 0), 0u) << bias;
  const std::string off =
      error_of(axis_file("sim", "step = 1\ndir = 2\nhome = { bias = \"pull-up\" }\n"));
  EXPECT_EQ(off.rfind("test.toml:8: key 'axis[1].home.offset': required", 0), 0u) << off;
  const std::string str = error_of(axis_file("sim", "step = 1\ndir = \"x\"\n"));
  EXPECT_EQ(str.rfind("test.toml:7: key 'axis[1].dir': must be an integer 0..4095", 0), 0u) << str;
  const std::string db =
      error_of(axis_file("sim", "step = 1\ndir = 2\nhome = { offset = 5, debounce_us = -1 }\n"));
  EXPECT_EQ(db.rfind("test.toml:8: key 'axis[1].home.debounce_us': must be", 0), 0u) << db;
}

TEST(ConfigLines, OffsetInATableIsCheckedForReuse) {
  const std::string e =
      error_of(axis_file("sim", "step = 1\ndir = 2\nhome = { offset = 2, bias = \"pull-up\" }\n"));
  EXPECT_NE(e.find("line offset 2 is already used by 'axis[1].dir'"), std::string::npos) << e;
}

TEST(ConfigLines, DebounceFollowsTheLibgpiodOfTheBuild) {
  const std::string text =
      axis_file("gpiod", "step = 1\ndir = 2\nhome = { offset = 5, debounce_us = 500 }\n");
  if (gpio::gpiod_capabilities().debounce) {
    EXPECT_EQ(error_of(text), "(accepted)");
  } else {
    EXPECT_EQ(error_of(text),
              "test.toml:8: key 'axis[1].home.debounce_us': kernel debounce needs libgpiod 2; "
              "this stepmod is built with libgpiod 1.x (v1 uAPI, no debounce): debounce in "
              "hardware (RC filter) or remove the key");
  }
  // The simulated machine's edges do not bounce: accepted whatever the libgpiod.
  EXPECT_EQ(
      error_of(axis_file("sim", "step = 1\ndir = 2\nhome = { offset = 5, debounce_us = 500 }\n")),
      "(accepted)");
}

TEST(ConfigLines, EnableLineAndItsKeys) {
  const Config c = parse_config(
      axis_file("sim",
                "step = 1\ndir = 2\nenable = { offset = 9, active_low = true }\n"
                "enable_delay_us = 250000\nenable_release_on = [\"estop\", \"plc_loss\"]\n"),
      "t");
  const auto& a = c.axes[0];
  EXPECT_EQ(a.enable, 9u);
  EXPECT_TRUE(a.enable_opt.active_low);
  EXPECT_EQ(a.enable_delay_ns, 250 * kNsPerMs);
  EXPECT_EQ(a.enable_release, kReleaseOnEStop | kReleaseOnPlcLoss);
  const Config d = parse_config(axis_file("sim", "step = 1\ndir = 2\nenable = 9\n"), "t");
  EXPECT_EQ(d.axes[0].enable_delay_ns, 10 * kNsPerMs);
  EXPECT_EQ(d.axes[0].enable_release, 0);
  EXPECT_FALSE(parse_config(axis_file("sim", "step = 1\ndir = 2\n"), "t").axes[0].enable);
}

TEST(ConfigLines, EnableKeysWithoutAnEnableLineOrWithBadValuesAreErrors) {
  EXPECT_EQ(error_of(axis_file("sim", "step = 1\ndir = 2\nenable_delay_us = 5\n")),
            "test.toml:8: key 'axis[1].enable_delay_us': needs an enable line (key 'enable')");
  const std::string bad = error_of(
      axis_file("sim", "step = 1\ndir = 2\nenable = 9\nenable_release_on = [\"estop\", \"x\"]\n"));
  EXPECT_EQ(bad.rfind("test.toml:9: key 'axis[1].enable_release_on': must be a list of", 0), 0u)
      << bad;
  const std::string twice = error_of(axis_file("sim", "step = 1\ndir = 2\nenable = 2\n"));
  EXPECT_NE(twice.find("line offset 2 is already used by 'axis[1].dir'"), std::string::npos)
      << twice;
}

// The [charge_pump] table (docs/interface.md section 2, docs/safety.md "Charge pump"): off without
// a line, its frequency a whole number of scans per half period, its line nobody else's (in the
// file, and in a rack on a real chip); each error names the file, the key and the fix.
std::string module_file(const std::string& more, const std::string& module_keys = "") {
  return "[module]\ntype = \"3601\"\n" + module_keys + "[[axis]]\nstep = 17\ndir = 27\n" + more;
}

TEST(ConfigChargePump, OffWithoutALine) {
  EXPECT_FALSE(parse_config(module_file(""), "t.toml").charge_pump.line.has_value());
  EXPECT_FALSE(parse_config(module_file("[charge_pump]\n"), "t.toml").charge_pump.line);
}

TEST(ConfigChargePump, LineAndDefaultFrequencyOfFiveScansPerHalfPeriod) {
  const Config c = parse_config(module_file("[charge_pump]\nline = 22\n"), "t.toml");
  ASSERT_TRUE(c.charge_pump.line.has_value());
  EXPECT_EQ(*c.charge_pump.line, 22u);
  EXPECT_EQ(c.charge_pump.frequency_hz, 100u);
  EXPECT_EQ(c.charge_pump.half_period_scans, 5u);  // 5 ms at scan_us = 1000
}

TEST(ConfigChargePump, LineTableAndFrequency) {
  const Config c = parse_config(
      module_file("[charge_pump]\nline = { offset = 22, active_low = true, drive = "
                  "\"open-drain\" }\nfrequency_hz = 250\n",
                  "scan_us = 500\n"),
      "t.toml");
  ASSERT_TRUE(c.charge_pump.line.has_value());
  EXPECT_TRUE(c.charge_pump.line_opt.active_low);
  EXPECT_EQ(c.charge_pump.line_opt.drive, gpio::Drive::kOpenDrain);
  EXPECT_EQ(c.charge_pump.half_period_scans, 4u);  // 2 ms at 500 us
}

TEST(ConfigChargePump, FrequencyNotAWholeNumberOfScansNamesTheOnesThatAre) {
  EXPECT_EQ(error_of(module_file("[charge_pump]\nline = 22\nfrequency_hz = 300\n")),
            "test.toml:8: key 'charge_pump.frequency_hz': 300 Hz is not a whole number of scans "
            "per half period at module.scan_us = 1000: use 500, 250, 125, 100, 50, 25, 20 or 10 "
            "Hz, or change module.scan_us");
  // The default, at a scan it does not divide: the table's line, "the default".
  const std::string e = error_of(module_file("[charge_pump]\nline = 22\n", "scan_us = 3000\n"));
  EXPECT_EQ(e.rfind("test.toml:7: key 'charge_pump.frequency_hz': the default 100 Hz is not a "
                    "whole number of scans per half period at module.scan_us = 3000",
                    0),
            0u)
      << e;
}

TEST(ConfigChargePump, FrequencyOutOfRange) {
  const std::string e = error_of(module_file("[charge_pump]\nline = 22\nfrequency_hz = 5\n"));
  EXPECT_NE(e.find("key 'charge_pump.frequency_hz': must be an integer 10..2000"),
            std::string::npos)
      << e;
}

TEST(ConfigChargePump, FrequencyWithoutALine) {
  EXPECT_EQ(error_of(module_file("[charge_pump]\nfrequency_hz = 100\n")),
            "test.toml:7: key 'charge_pump.frequency_hz': needs a line (key 'charge_pump.line')");
}

TEST(ConfigChargePump, UnknownKeyListsTheTablesKeys) {
  const std::string e = error_of(module_file("[charge_pump]\npin = 22\n"));
  EXPECT_NE(e.find("charge_pump.pin"), std::string::npos) << e;
  EXPECT_NE(e.find("frequency_hz"), std::string::npos) << e;
}

TEST(ConfigChargePump, ALineOfAnotherFunctionIsRefused) {
  EXPECT_EQ(error_of(module_file("[charge_pump]\nline = 27\n")),
            "test.toml:7: key 'charge_pump.line': line offset 27 is already used by 'axis[1].dir'");
  EXPECT_EQ(
      error_of(module_file("enable = 22\n[charge_pump]\nline = { offset = 22 }\n")),
      "test.toml:8: key 'charge_pump.line': line offset 22 is already used by 'axis[1].enable'");
}

// On a real chip a rack's modules never share a line: the pump's neither.
TEST(ConfigChargePump, RackRefusesAPumpOnAnotherModulesLine) {
  namespace fs = std::filesystem;
  std::string tmpl = (fs::temp_directory_path() / "stepmod-pump-XXXXXX").string();
  ASSERT_NE(::mkdtemp(tmpl.data()), nullptr);
  const fs::path dir = tmpl;
  const auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
  };
  const std::string gpiod = "[gpio]\nbackend = \"gpiod\"\n";
  write("x.toml", module_file("", "name = \"x\"\n" + gpiod));
  write("y.toml", "[module]\ntype = \"3601\"\nname = \"y\"\n" + gpiod +
                      "[[axis]]\nstep = 5\ndir = 6\n[charge_pump]\nline = 17\n");
  write("rack.toml", "[rack]\nmodules = [\"x.toml\", \"y.toml\"]\n");
  std::string e = "(accepted)";
  try {
    load_rack((dir / "rack.toml").string());
  } catch (const ConfigError& err) {
    e = err.what();
  }
  fs::remove_all(dir);
  EXPECT_NE(e.find("key 'charge_pump.line' of module 'y'"), std::string::npos) << e;
  EXPECT_NE(e.find("already used by key 'axis[1].step' of module 'x'"), std::string::npos) << e;
}

}  // namespace
}  // namespace stepmod::tools

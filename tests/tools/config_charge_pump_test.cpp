// The [charge_pump] table (docs/interface.md section 2, docs/safety.md "Charge pump"): off without
// a line, its frequency a whole number of scans per half period, its line nobody else's (in the
// file, and in a rack on a real chip); each error names the file, the key and the fix.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "config/config.hpp"
#include "config/rack_config.hpp"

namespace stepmod::tools {
namespace {

namespace fs = std::filesystem;

std::string module_file(const std::string& more, const std::string& module_keys = "") {
  return "[module]\ntype = \"3601\"\n" + module_keys + "[[axis]]\nstep = 17\ndir = 27\n" + more;
}

std::string error_of(const std::string& text) {
  try {
    parse_config(text, "test.toml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(accepted)";
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

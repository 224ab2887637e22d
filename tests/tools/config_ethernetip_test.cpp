// [ethernetip] (docs/ethernetip-design.md, "Where it sits in stepmod"): off by default with the
// contract's defaults, a full valid table, and one test per error, each naming the file, the
// key and the fix (stepmodd exits 2 on every ConfigError).
#include <gtest/gtest.h>

#include <string>

#include "config/config.hpp"
#include "tests/tools/one_table_config.hpp"

namespace stepmod::tools {
namespace {

// The options in one line: "on|off ADDRESS:PORT allow N rpi MIN..MAX".
std::string summary(const enip::AdapterOptions& e) {
  return std::string(e.enabled ? "on " : "off ") + e.address + ":" + std::to_string(e.port) +
         " allow " + std::to_string(e.allow.size()) + " rpi " + std::to_string(e.rpi_min_us) +
         ".." + std::to_string(e.rpi_max_us);
}

TEST(ConfigEthernetIp, OffByDefaultWithContractDefaults) {
  EXPECT_EQ(summary(parse_config(kBase, "t.toml").ethernetip),
            "off 127.0.0.1:44818 allow 0 rpi 1000..100000");
  // An empty table changes nothing either.
  EXPECT_EQ(summary(parse_config(std::string(kBase) + "[ethernetip]\n", "t.toml").ethernetip),
            "off 127.0.0.1:44818 allow 0 rpi 1000..100000");
}

TEST(ConfigEthernetIp, FullTable) {
  const std::string table = R"([ethernetip]
enabled = true
listen = "10.0.0.5:44818"
allow = ["10.0.0.1", "192.168.0.0/16"]
rpi_min_us = 2000
rpi_max_us = 50000
)";
  const enip::AdapterOptions e = parse_config(std::string(kBase) + table, "t.toml").ethernetip;
  EXPECT_EQ(summary(e), "on 10.0.0.5:44818 allow 2 rpi 2000..50000");
  ASSERT_EQ(e.allow.size(), 2u);
  EXPECT_EQ(e.allow[0].network, 0x0A000001u);
  EXPECT_EQ(e.allow[1].mask, 0xFFFF0000u);
}

// The contract's own block writes `allow = []` for "any originator that can reach listen".
TEST(ConfigEthernetIp, EmptyAllowListMeansAnySource) {
  const std::string table = "[ethernetip]\nenabled = true\nallow = []\n";
  EXPECT_EQ(summary(parse_config(std::string(kBase) + table, "t.toml").ethernetip),
            "on 127.0.0.1:44818 allow 0 rpi 1000..100000");
}

TEST(ConfigEthernetIp, BadListenNamesTheKeyAndTheForm) {
  const std::string e = error_of("[ethernetip]\nlisten = \"localhost:44818\"\n");
  EXPECT_NE(e.find("test.toml"), std::string::npos) << e;
  EXPECT_NE(e.find("ethernetip.listen"), std::string::npos) << e;
  EXPECT_NE(e.find("IPv4-ADDRESS:PORT"), std::string::npos) << e;
  EXPECT_NE(error_of("[ethernetip]\nlisten = \"127.0.0.1:0\"\n").find("ethernetip.listen"),
            std::string::npos);
}

TEST(ConfigEthernetIp, BadAllowNamesTheKey) {
  for (const char* bad : {"allow = [\"10.0.0.0/33\"]\n", "allow = \"any\"\n", "allow = [1]\n"}) {
    const std::string e = error_of(std::string("[ethernetip]\n") + bad);
    EXPECT_NE(e.find("ethernetip.allow"), std::string::npos) << bad << ": " << e;
  }
}

TEST(ConfigEthernetIp, RpiRangeIsChecked) {
  std::string e = error_of("[ethernetip]\nrpi_min_us = 100\n");
  EXPECT_NE(e.find("rpi_min_us"), std::string::npos) << e;
  e = error_of("[ethernetip]\nrpi_min_us = 5000\nrpi_max_us = 4000\n");
  EXPECT_NE(e.find("ethernetip.rpi_max_us"), std::string::npos) << e;
  EXPECT_NE(e.find("below ethernetip.rpi_min_us"), std::string::npos) << e;
  EXPECT_NE(e.find("test.toml:10"), std::string::npos) << e;
}

TEST(ConfigEthernetIp, UnknownKeyIsRefused) {
  const std::string e = error_of("[ethernetip]\nport = 44818\n");
  EXPECT_NE(e.find("ethernetip.port"), std::string::npos) << e;
}

}  // namespace
}  // namespace stepmod::tools

// [ethernetip] (docs/ethernetip-design.md, "Where it sits in stepmod"): off by default with the
// contract's defaults, a full valid table, and one test per error, each naming the file, the
// key and the fix (stepmodd exits 2 on every ConfigError).
#include <gtest/gtest.h>

#include <arpa/inet.h>

#include <string>

#include "config/config.hpp"

namespace stepmod::tools {
namespace {

constexpr const char* kBase = R"([module]
type = "3601"

[[axis]]
step = 17
dir = 27

)";  // [ethernetip] starts on line 8

std::string error_of(const std::string& table) {
  try {
    parse_config(std::string(kBase) + table, "test.toml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(ConfigEthernetIp, OffByDefaultWithContractDefaults) {
  const Config c = parse_config(kBase, "t.toml");
  EXPECT_FALSE(c.ethernetip.enabled);
  EXPECT_EQ(c.ethernetip.address, "127.0.0.1");
  EXPECT_EQ(c.ethernetip.port, 44818);
  EXPECT_TRUE(c.ethernetip.allow.empty());
  EXPECT_EQ(c.ethernetip.rpi_min_us, 1000u);
  EXPECT_EQ(c.ethernetip.rpi_max_us, 100000u);
  EXPECT_FALSE(parse_config(std::string(kBase) + "[ethernetip]\n", "t.toml").ethernetip.enabled);
}

TEST(ConfigEthernetIp, FullTable) {
  const Config c = parse_config(std::string(kBase) + R"([ethernetip]
enabled = true
listen = "10.0.0.5:44818"
allow = ["10.0.0.1", "192.168.0.0/16"]
rpi_min_us = 2000
rpi_max_us = 50000
)",
                                "t.toml");
  EXPECT_TRUE(c.ethernetip.enabled);
  EXPECT_EQ(c.ethernetip.address, "10.0.0.5");
  EXPECT_EQ(c.ethernetip.port, 44818);
  ASSERT_EQ(c.ethernetip.allow.size(), 2u);
  EXPECT_EQ(c.ethernetip.allow[0].network, 0x0A000001u);
  EXPECT_EQ(c.ethernetip.allow[1].mask, 0xFFFF0000u);
  EXPECT_EQ(c.ethernetip.rpi_min_us, 2000u);
  EXPECT_EQ(c.ethernetip.rpi_max_us, 50000u);
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
  for (const char* bad : {"allow = []\n", "allow = [\"10.0.0.0/33\"]\n", "allow = \"any\"\n"}) {
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

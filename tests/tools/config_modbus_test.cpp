// [modbus] (docs/interface.md 6): defaults, a full valid table, and one test per error (file, key,
// line; exit status 2 comes from stepmodd's handling of every ConfigError).
#include <gtest/gtest.h>

#include <string>

#include "config/config.hpp"
#include "tests/tools/one_table_config.hpp"

namespace stepmod::tools {
namespace {

TEST(ConfigModbus, OffByDefaultWithContractDefaults) {
  const Config c = parse_config(kBase, "t.toml");
  EXPECT_FALSE(c.modbus.enabled);
  EXPECT_EQ(c.modbus.address, "127.0.0.1");
  EXPECT_EQ(c.modbus.port, 1502);
  EXPECT_EQ(c.modbus.unit_id, 1);
  EXPECT_FALSE(c.modbus.writes);
  EXPECT_EQ(c.modbus.max_clients, 4u);
  EXPECT_EQ(c.modbus.idle_timeout_ms, 5000u);
  // An empty table changes nothing either.
  EXPECT_FALSE(parse_config(std::string(kBase) + "[modbus]\n", "t.toml").modbus.enabled);
}

TEST(ConfigModbus, FullTable) {
  const Config c = parse_config(std::string(kBase) + R"([modbus]
enabled = true
listen = "0.0.0.0:5020"
unit_id = 17
writes = true
max_clients = 9
idle_timeout_ms = 250
)",
                                "t.toml");
  EXPECT_TRUE(c.modbus.enabled);
  EXPECT_EQ(c.modbus.address, "0.0.0.0");
  EXPECT_EQ(c.modbus.port, 5020);
  EXPECT_EQ(c.modbus.unit_id, 17);
  EXPECT_TRUE(c.modbus.writes);
  EXPECT_EQ(c.modbus.max_clients, 9u);
  EXPECT_EQ(c.modbus.idle_timeout_ms, 250u);
}

TEST(ConfigModbusError, UnknownKey) {
  EXPECT_EQ(error_of("[modbus]\nport = 502\n"),
            "test.toml:9: key 'modbus.port': unknown key (expected one of: enabled, listen, "
            "unit_id, writes, max_clients, idle_timeout_ms, allow)");
}

TEST(ConfigModbusError, BooleansMustBeBooleans) {
  EXPECT_EQ(error_of("[modbus]\nenabled = \"yes\"\n"),
            "test.toml:9: key 'modbus.enabled': must be true or false");
  EXPECT_EQ(error_of("[modbus]\nwrites = 1\n"),
            "test.toml:9: key 'modbus.writes': must be true or false");
}

TEST(ConfigModbusError, ListenNeedsIpv4AndPort) {
  const std::string msg =
      "test.toml:9: key 'modbus.listen': must be \"IPv4-ADDRESS:PORT\" with a port 1..65535, e.g. "
      "\"127.0.0.1:1502\"";
  for (const char* bad : {"\"127.0.0.1\"", "\"localhost:1502\"", "\"127.0.0.1:0\"",
                          "\"127.0.0.1:65536\"", "\"127.0.0.1:15x2\"", "\":1502\"",
                          "\"127.0.0.256:1502\"", "\"127.0.0.1:-1\"", "1502", "\"\""}) {
    EXPECT_EQ(error_of(std::string("[modbus]\nlisten = ") + bad + "\n"), msg) << bad;
  }
}

TEST(ConfigModbusError, Ranges) {
  EXPECT_EQ(error_of("[modbus]\nunit_id = 256\n"),
            "test.toml:9: key 'modbus.unit_id': must be an integer 0..255");
  EXPECT_EQ(error_of("[modbus]\nunit_id = -1\n"),
            "test.toml:9: key 'modbus.unit_id': must be an integer 0..255");
  EXPECT_EQ(error_of("[modbus]\nmax_clients = 0\n"),
            "test.toml:9: key 'modbus.max_clients': must be an integer 1..64");
  EXPECT_EQ(error_of("[modbus]\nmax_clients = 65\n"),
            "test.toml:9: key 'modbus.max_clients': must be an integer 1..64");
  EXPECT_EQ(error_of("[modbus]\nidle_timeout_ms = 99\n"),
            "test.toml:9: key 'modbus.idle_timeout_ms': must be an integer 100..3600000");
  EXPECT_EQ(error_of("[modbus]\nidle_timeout_ms = 3600001\n"),
            "test.toml:9: key 'modbus.idle_timeout_ms': must be an integer 100..3600000");
  EXPECT_EQ(error_of("[modbus]\nidle_timeout_ms = 2.5\n"),
            "test.toml:9: key 'modbus.idle_timeout_ms': must be an integer 100..3600000");
}

TEST(ConfigModbusError, MustBeATable) {
  try {
    parse_config("modbus = true\n" + std::string(kBase), "test.toml");
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "test.toml:1: key 'modbus': must be a table [modbus]");
  }
}

TEST(ConfigModbus, AllowListOfAddressesAndNetworks) {
  const Config c = parse_config(
      std::string(kBase) + "[modbus]\nallow = [\"127.0.0.1\", \"10.0.0.0/8\"]\n", "t.toml");
  ASSERT_EQ(c.modbus.allow.size(), 2u);
  EXPECT_EQ(c.modbus.allow[0].network, 0x7F000001u);
  EXPECT_EQ(c.modbus.allow[0].mask, 0xFFFFFFFFu);
  EXPECT_EQ(c.modbus.allow[1].network, 0x0A000000u);
  EXPECT_EQ(c.modbus.allow[1].mask, 0xFF000000u);
  EXPECT_TRUE(parse_config(kBase, "t.toml").modbus.allow.empty()) << "no list: any source";
}

TEST(ConfigModbusError, AllowEntriesMustBeIpv4AddressesOrNetworks) {
  const std::string entry =
      "test.toml:9: key 'modbus.allow': each entry must be an IPv4 address or ADDRESS/PREFIX "
      "(0..32) in quotes, e.g. \"10.0.0.0/8\"";
  for (const char* bad : {"[\"localhost\"]", "[\"10.0.0.0/33\"]", "[\"::1\"]", "[10]",
                          "[\"127.0.0.1\", \"10.0.0.0/\"]"}) {
    EXPECT_EQ(error_of(std::string("[modbus]\nallow = ") + bad + "\n"), entry) << bad;
  }
  const std::string list =
      "test.toml:9: key 'modbus.allow': must be a non-empty list of IPv4 addresses or networks, "
      "e.g. [\"127.0.0.1\", \"10.0.0.0/8\"]";
  EXPECT_EQ(error_of("[modbus]\nallow = \"127.0.0.1\"\n"), list);
  EXPECT_EQ(error_of("[modbus]\nallow = []\n"), list);
}

}  // namespace
}  // namespace stepmod::tools

// The parser takes every default and range from the key table (config/config_keys.hpp): a file
// that leaves a key out gets the row's default, a value at either bound of the row's range is
// accepted and read, one beyond it refused with the range in the message. Driven by the rows, so
// a default or bound stated anywhere else in the parser fails here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include "config/config.hpp"
#include "config/config_keys.hpp"

namespace stepmod::tools {
namespace {

using Read = std::function<std::int64_t(const Config&)>;

// Each numeric key's value as the parser stored it, in the key's own unit.
const std::map<std::string, Read>& readers() {
  static const std::map<std::string, Read> r = {
      {"module.scan_us", [](const Config& c) { return c.scan_ns / kNsPerUs; }},
      {"module.plc_timeout_ms", [](const Config& c) { return c.plc_timeout_ns / kNsPerMs; }},
      {"rt.priority", [](const Config& c) { return c.rt_priority; }},
      {"rt.cpu", [](const Config& c) { return c.rt_cpu; }},
      {"rt.late_limit_us", [](const Config& c) { return c.late_limit_ns / kNsPerUs; }},
      {"axis.step_pulse_ns", [](const Config& c) { return c.axes[0].step_pulse_ns; }},
      {"axis.dir_setup_ns", [](const Config& c) { return c.axes[0].dir_setup_ns; }},
      {"axis.lag_limit_steps", [](const Config& c) { return c.axes[0].lag_limit_steps; }},
      {"axis.enable_delay_us",
       [](const Config& c) { return c.axes[0].enable_delay_ns / kNsPerUs; }},
      {"axis.sim.start_position", [](const Config& c) { return c.axes[0].sim.start_position; }},
      {"axis.sim.cw_limit_at", [](const Config& c) { return c.axes[0].sim.cw_limit_at.value(); }},
      {"axis.sim.ccw_limit_at", [](const Config& c) { return c.axes[0].sim.ccw_limit_at.value(); }},
      {"axis.sim.home_from", [](const Config& c) { return c.axes[0].sim.home_from.value(); }},
      {"axis.sim.home_to", [](const Config& c) { return c.axes[0].sim.home_to.value(); }},
      {"axis.sim.encoder_ratio",
       [](const Config& c) { return static_cast<std::int64_t>(c.axes[0].sim.encoder_ratio); }},
      {"axis.sim.marker_every", [](const Config& c) { return c.axes[0].sim.marker_every.value(); }},
      {"axis.sim.event_ring",
       [](const Config& c) { return static_cast<std::int64_t>(c.axes[0].sim.event_ring); }},
      {"modbus.enabled", [](const Config& c) { return c.modbus.enabled ? 1 : 0; }},
      {"modbus.writes", [](const Config& c) { return c.modbus.writes ? 1 : 0; }},
      {"modbus.unit_id", [](const Config& c) { return c.modbus.unit_id; }},
      {"modbus.max_clients", [](const Config& c) { return c.modbus.max_clients; }},
      {"modbus.idle_timeout_ms", [](const Config& c) { return c.modbus.idle_timeout_ms; }},
      {"ethernetip.enabled", [](const Config& c) { return c.ethernetip.enabled ? 1 : 0; }},
      {"ethernetip.rpi_min_us", [](const Config& c) { return c.ethernetip.rpi_min_us; }},
      {"ethernetip.rpi_max_us", [](const Config& c) { return c.ethernetip.rpi_max_us; }},
      {"charge_pump.frequency_hz", [](const Config& c) { return c.charge_pump.frequency_hz; }},
  };
  return r;
}

constexpr const char* kModule = "[module]\ntype = \"3601\"\n";
constexpr const char* kAxis = "[[axis]]\nstep = 1\ndir = 2\n";
const std::string kMinimal = std::string(kModule) + kAxis;

// A valid 3601 file with `k` = `value` (and the keys it needs beside it).
std::string file_with(const ConfigKey& k, std::int64_t value) {
  const std::string v = std::to_string(value);
  const std::string kv = std::string(k.key) + " = " + v + "\n";
  if (k.table == "module") return kModule + kv + kAxis;
  // The pump's frequency needs its line, and a scan its bounds' half periods are whole ones of.
  if (k.table == "charge_pump") {
    const std::string line = k.key == "line" ? "" : "line = 3\n";
    return kModule + std::string("scan_us = 250\n") + kAxis + "[charge_pump]\n" + line + kv;
  }
  if (k.table != "axis" && k.table != "axis.sim") {
    return std::string(kMinimal) + "[" + std::string(k.table) + "]\n" + kv;
  }
  std::string axis = "[[axis]]\n";
  axis += k.key == "step" ? kv : "step = 1\n";
  axis += k.key == "dir" ? kv : "dir = 2\n";
  if (k.table == "axis" && k.key != "step" && k.key != "dir") axis += kv;
  if (k.key == "enable_delay_us") axis += "enable = 3\n";
  if (k.key == "enc_a") axis += "enc_b = 3\n";
  if (k.key == "enc_b") axis += "enc_a = 3\n";
  if (k.table == "axis.sim") {
    axis += "[axis.sim]\n" + kv;
    // The other end of the home switch: valid, so that the message names `k`.
    const std::string other = std::to_string(std::clamp(value, k.min, k.max));
    if (k.key == "home_from") axis += "home_to = " + other + "\n";
    if (k.key == "home_to") axis = kAxis + ("[axis.sim]\nhome_from = " + other + "\n") + kv;
  }
  const std::string type = k.key == "gpo" ? "3602" : "3601";
  const std::string second = type == "3602" ? "[[axis]]\nstep = 10\ndir = 11\n" : "";
  return "[module]\ntype = \"" + type + "\"\n" + axis + second;
}

// How a message names `k` in [[axis]] 1.
std::string message_name(const ConfigKey& k) {
  if (k.table == "axis") return "axis[1]." + std::string(k.key);
  if (k.table == "axis.sim") return "axis[1].sim." + std::string(k.key);
  return config_key_name(k);
}

std::string error_of(const std::string& text) {
  try {
    parse_config(text, "t.toml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(accepted)";
}

bool ranged(const ConfigKey& k) {
  return k.type == KeyType::kInt || k.type == KeyType::kNumber || k.type == KeyType::kLine;
}

TEST(ConfigTable, AKeyLeftOutGetsTheRowsDefault) {
  const Config c = parse_config(kMinimal, "t.toml");
  for (const ConfigKey& k : kConfigKeys) {
    if (k.absent != Absent::kDefault || !(ranged(k) || k.type == KeyType::kBool)) continue;
    const auto read = readers().find(config_key_name(k));
    ASSERT_NE(read, readers().end()) << config_key_name(k) << ": add it to readers()";
    EXPECT_EQ(read->second(c), k.def) << config_key_name(k);
  }
  EXPECT_EQ(c.name, config_key("module", "name").text);
  EXPECT_EQ(c.chip, config_key("gpio", "chip").text);
  EXPECT_EQ(c.backend == Config::Backend::kSim, config_key("gpio", "backend").text == "sim");
  EXPECT_EQ(c.axes[0].sim.contacts_nc, config_key("axis.sim", "contacts").text == "NC");
  EXPECT_EQ(c.modbus.address + ":" + std::to_string(c.modbus.port),
            config_key("modbus", "listen").text);
  EXPECT_TRUE(c.modbus.allow.empty());
  EXPECT_EQ(c.ethernetip.address + ":" + std::to_string(c.ethernetip.port),
            config_key("ethernetip", "listen").text);
  EXPECT_TRUE(c.ethernetip.allow.empty());
  EXPECT_EQ(c.axes[0].enable_release, 0);
}

TEST(ConfigTable, EachBoundIsAcceptedAndOneBeyondRefused) {
  for (const ConfigKey& k : kConfigKeys) {
    if (!ranged(k)) continue;
    const std::string name = config_key_name(k);
    for (const std::int64_t v : {k.min, k.max}) {
      if (v == kUnbounded) continue;
      const std::string text = file_with(k, v);
      EXPECT_EQ(error_of(text), "(accepted)") << name << " = " << v << " in\n" << text;
      const auto read = readers().find(name);
      if (read != readers().end() && error_of(text) == "(accepted)") {
        EXPECT_EQ(read->second(parse_config(text, "t.toml")), v) << name;
      }
    }
    const std::string range =
        k.type == KeyType::kNumber
            ? "must be a finite number, " + std::to_string(k.min) + " .. " + std::to_string(k.max)
        : k.max == kUnbounded
            ? "must be an integer >= " + std::to_string(k.min)
            : "must be an integer " + std::to_string(k.min) + ".." + std::to_string(k.max);
    const std::string want = "key '" + message_name(k) + "': " + range;
    EXPECT_NE(error_of(file_with(k, k.min - 1)).find(want), std::string::npos)
        << name << " = " << k.min - 1 << ": " << error_of(file_with(k, k.min - 1));
    if (k.max != kUnbounded) {
      EXPECT_NE(error_of(file_with(k, k.max + 1)).find(want), std::string::npos)
          << name << " = " << k.max + 1 << ": " << error_of(file_with(k, k.max + 1));
    }
  }
}

// The line options' bounds (a line table's offset and debounce_us) from their rows too.
TEST(ConfigTable, LineOptionBoundsAreTheRows) {
  for (const char* key : {"offset", "debounce_us"}) {
    const ConfigKey& k = *find_config_key("line", key);
    const auto home = [&](std::int64_t v) {
      const std::string offset = std::string(key) == "offset" ? "" : "offset = 5, ";
      return kMinimal + "home = { " + offset + key + " = " + std::to_string(v) + " }\n";
    };
    EXPECT_EQ(error_of(home(k.min)), "(accepted)") << key;
    EXPECT_EQ(error_of(home(k.max)), "(accepted)") << key;
    const std::string want = "key 'axis[1].home." + std::string(key) + "': must be an integer " +
                             std::to_string(k.min) + ".." + std::to_string(k.max);
    EXPECT_NE(error_of(home(k.min - 1)).find(want), std::string::npos) << error_of(home(k.min - 1));
    EXPECT_NE(error_of(home(k.max + 1)).find(want), std::string::npos) << error_of(home(k.max + 1));
  }
}

}  // namespace
}  // namespace stepmod::tools

// The configuration keys as documented against the keys the parser accepts
// (config/config_keys.hpp): docs/interface.md's key table and the stepmod.toml(5) man page list
// exactly those keys, so that a key added to the parser cannot go undocumented and a documented
// key cannot be one the parser refuses. And every key of the table is accepted by the parser.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <toml++/toml.h>

#include "config/config.hpp"
#include "config/config_keys.hpp"

namespace stepmod::tools {
namespace {

std::string read_source_file(const std::string& relative) {
  const std::string path = std::string(STEPMOD_SOURCE_DIR) + "/" + relative;
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << "cannot read " << path;
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::set<std::string> parser_keys() {
  const std::vector<std::string> names = config_value_key_names();
  return {names.begin(), names.end()};
}

// The text between the first line containing `begin` and the next line containing `end`.
std::string section(const std::string& text, const std::string& begin, const std::string& end) {
  const auto from = text.find(begin);
  if (from == std::string::npos) return {};
  const auto to = text.find(end, from + begin.size());
  return text.substr(from, to == std::string::npos ? std::string::npos : to - from);
}

std::set<std::string> matches(const std::string& text, const std::regex& re) {
  std::set<std::string> keys;
  for (std::sregex_iterator it(text.begin(), text.end(), re), last; it != last; ++it) {
    keys.insert((*it)[1]);
  }
  return keys;
}

// What is in `documented` and not in `parser`, and the other way round, for the failure message.
std::string difference(const std::set<std::string>& documented,
                       const std::set<std::string>& parser) {
  std::string out;
  for (const auto& k : parser) {
    if (!documented.count(k)) out += "  undocumented (accepted by the parser): " + k + "\n";
  }
  for (const auto& k : documented) {
    if (!parser.count(k)) out += "  documented but refused by the parser: " + k + "\n";
  }
  return out;
}

TEST(ConfigKeysDoc, InterfaceMdKeyTableListsExactlyTheParserKeys) {
  const std::string table = section(read_source_file("docs/interface.md"), "<!-- config-keys:begin",
                                    "<!-- config-keys:end");
  ASSERT_FALSE(table.empty()) << "docs/interface.md has no config-keys:begin/end markers";
  const auto documented = matches(table, std::regex(R"(\n\| `([a-z_]+(?:\.[a-z_]+)+)` \|)"));
  EXPECT_EQ(documented, parser_keys()) << "docs/interface.md section 2:\n"
                                       << difference(documented, parser_keys());
}

TEST(ConfigKeysDoc, ManPageKeysSectionListsExactlyTheParserKeys) {
  const std::string keys =
      section(read_source_file("packaging/man/stepmod.toml.5"), "\n.SH KEYS", "\n.SH LATE");
  ASSERT_FALSE(keys.empty()) << "stepmod.toml.5 has no KEYS section";
  const auto documented = matches(keys, std::regex(R"(\n\.B ([a-z_]+(?:\.[a-z_]+)+)\n)"));
  EXPECT_EQ(documented, parser_keys()) << "packaging/man/stepmod.toml.5, KEYS:\n"
                                       << difference(documented, parser_keys());
}

// Every value key of `t`, as "table.key", [[axis]] arrays flattened to "axis".
void collect_keys(const toml::table& t, const std::string& prefix, std::set<std::string>& out) {
  for (auto&& [k, v] : t) {
    const std::string name =
        prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    if (const auto* sub = v.as_table()) {
      collect_keys(*sub, name, out);
    } else if (const auto* arr = v.as_array(); arr != nullptr && arr->is_array_of_tables()) {
      for (auto&& e : *arr) collect_keys(*e.as_table(), name, out);
    } else {
      out.insert(name);
    }
  }
}

// Every table entry is a key the parser takes: a 3601 file that sets every key of the table
// but the 3602-only gpo parses, and so does a 3602 file with gpo.
TEST(ConfigKeysDoc, ParserAcceptsEveryKeyOfTheTable) {
  const std::string every_key = R"(
[module]
type = "3601"
name = "keys"
scan_us = 1000
plc_timeout_ms = 0
[gpio]
backend = "sim"
chip = "gpiochip0"
[rt]
priority = 80
cpu = -1
late_limit_us = 1000
[[axis]]
step = 1
dir = 2
capture = 3
external = 4
home = 5
estop = 6
cw_limit = 7
ccw_limit = 8
enc_a = 9
enc_b = 10
enc_z = 11
step_pulse_ns = 2000
dir_setup_ns = 5000
lag_limit_steps = 8
enable = 12
enable_delay_us = 10000
enable_release_on = ["estop"]
[axis.sim]
start_position = 0
cw_limit_at = 100
ccw_limit_at = -100
home_from = 10
home_to = 20
contacts = "NO"
encoder_ratio = 1.0
marker_every = 4000
event_ring = 65536
[modbus]
enabled = false
listen = "127.0.0.1:1502"
unit_id = 1
writes = false
max_clients = 4
idle_timeout_ms = 5000
allow = ["127.0.0.1"]
[ethernetip]
enabled = false
listen = "127.0.0.1:44818"
allow = ["127.0.0.1"]
rpi_min_us = 1000
rpi_max_us = 100000
[charge_pump]
line = 13
frequency_hz = 100
)";
  EXPECT_EQ(parse_config(every_key, "keys.toml").name, "keys");
  std::set<std::string> written;
  collect_keys(toml::parse(every_key), "", written);
  written.insert("axis.gpo");
  EXPECT_EQ(written, parser_keys()) << "a key was added to the table: add it to the file above\n"
                                    << difference(written, parser_keys());

  const Config c3602 = parse_config(
      "[module]\ntype = \"3602\"\n[[axis]]\nstep = 1\ndir = 2\ngpo = 3\n"
      "[[axis]]\nstep = 4\ndir = 5\n",
      "gpo.toml");
  EXPECT_TRUE(c3602.axes[0].out[2].has_value());
}

TEST(ConfigKeysDoc, UnknownKeyMessageListsTheTablesKeys) {
  try {
    parse_config("[module]\ntype = \"3601\"\n[rt]\nlate_limit = 5\n[[axis]]\nstep = 1\ndir = 2\n",
                 "typo.toml");
    FAIL() << "an unknown key was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("key 'rt.late_limit': unknown key (expected one of: "
                                         "priority, cpu, late_limit_us)"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace stepmod::tools

#pragma once
// Every key the configuration file accepts, table by table. The parser's unknown-key check reads
// it (tools/config.cpp), and a test checks that docs/interface.md and the stepmod.toml(5) man page
// list exactly these keys (tests/tools/config_keys_doc_test.cpp): a key added to the parser
// without its documentation fails the suite.
#include <string>
#include <string_view>
#include <vector>

namespace stepmod::tools {

struct ConfigKey {
  std::string_view table;  // "" = the file's top level; "axis.sim" = [axis.sim] of an [[axis]]
  std::string_view key;
  bool is_table = false;  // a sub-table ([module], [axis.sim]), not a value
};

inline constexpr ConfigKey kConfigKeys[] = {
    {"", "module", true},
    {"", "gpio", true},
    {"", "rt", true},
    {"", "axis", true},
    {"", "modbus", true},
    {"module", "type"},
    {"module", "name"},
    {"module", "scan_us"},
    {"module", "plc_timeout_ms"},
    {"gpio", "backend"},
    {"gpio", "chip"},
    {"rt", "priority"},
    {"rt", "cpu"},
    {"rt", "late_limit_us"},
    {"axis", "step"},
    {"axis", "dir"},
    {"axis", "gpo"},
    {"axis", "capture"},
    {"axis", "external"},
    {"axis", "home"},
    {"axis", "estop"},
    {"axis", "cw_limit"},
    {"axis", "ccw_limit"},
    {"axis", "enc_a"},
    {"axis", "enc_b"},
    {"axis", "enc_z"},
    {"axis", "step_pulse_ns"},
    {"axis", "dir_setup_ns"},
    {"axis", "lag_limit_steps"},
    {"axis", "enable"},
    {"axis", "enable_delay_us"},
    {"axis", "enable_release_on"},
    {"axis", "sim", true},
    {"axis.sim", "start_position"},
    {"axis.sim", "cw_limit_at"},
    {"axis.sim", "ccw_limit_at"},
    {"axis.sim", "home_from"},
    {"axis.sim", "home_to"},
    {"axis.sim", "contacts"},
    {"axis.sim", "encoder_ratio"},
    {"axis.sim", "marker_every"},
    {"axis.sim", "event_ring"},
    {"modbus", "enabled"},
    {"modbus", "listen"},
    {"modbus", "unit_id"},
    {"modbus", "writes"},
    {"modbus", "max_clients"},
    {"modbus", "idle_timeout_ms"},
    {"modbus", "allow"},
};

// The keys allowed directly in `table` (values and sub-tables), in the order above.
inline std::vector<std::string_view> config_keys_of(std::string_view table) {
  std::vector<std::string_view> keys;
  for (const ConfigKey& k : kConfigKeys) {
    if (k.table == table) keys.push_back(k.key);
  }
  return keys;
}

// Every value key as the docs write it: "module.type", "axis.sim.home_from".
inline std::vector<std::string> config_value_key_names() {
  std::vector<std::string> names;
  for (const ConfigKey& k : kConfigKeys) {
    if (!k.is_table) names.push_back(std::string(k.table) + "." + std::string(k.key));
  }
  return names;
}

}  // namespace stepmod::tools

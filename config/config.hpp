#pragma once
// The daemon's configuration file (docs/interface.md section 2), parsed and validated. A bad file
// is reported with the file, the key, the problem and the line, and nothing is started.
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "config/config_keys.hpp"
#include "core/clock.hpp"
#include "fieldbus/enip/adapter_options.hpp"
#include "gpio/axis_lines.hpp"
#include "gpio/backend.hpp"
#include "gpio/sim_machine.hpp"
#include "ipc/modbus_options.hpp"
#include "module/personality.hpp"

namespace stepmod::tools {

// [axis.sim]: the simulated machine's parameters are the sim backend's own.
using SimAxisConfig = gpio::SimAxisParams;

// One [[axis]] table. The line offsets (`out[]`, `in[]`, absent = not wired; step and dir are
// required) are the backend's AxisLines.
// What releases a drive-enable output besides the axis not being configured (bits of
// AxisSection::enable_release; config key enable_release_on).
enum EnableRelease : std::uint8_t {
  kReleaseOnEStop = 1,       // an E-stop input is active
  kReleaseOnFault = 2,       // a late-edge fault or lost input events stopped the axis
  kReleaseOnPlcLoss = 4,     // the PLC is lost (heartbeat stale, sequence stuck)
  kReleaseOnConfigMode = 8,  // the axis is in configuration mode
};

// One [[axis]] section of the config file: its lines, timings, drive enable and simulator. The
// initial values are the keys' defaults (config/config_keys.hpp), as the parser leaves them
// for a key the file leaves out.
struct AxisSection : gpio::AxisLines {
  Nanos step_pulse_ns = default_ns(config_key("axis", "step_pulse_ns"));
  Nanos dir_setup_ns = default_ns(config_key("axis", "dir_setup_ns"));
  // Late-edge guard above Vs (docs/slip.md): output steps the axis may lag after a pause.
  std::uint32_t lag_limit_steps =
      static_cast<std::uint32_t>(config_key("axis", "lag_limit_steps").def);
  // Drive-enable output (AxisLines::enable): commands wait this long after asserting it.
  Nanos enable_delay_ns = default_ns(config_key("axis", "enable_delay_us"));
  std::uint8_t enable_release = 0;  // EnableRelease bits
  SimAxisConfig sim;
};

// The [charge_pump] table (an extension, docs/safety.md "Charge pump"): a line that toggles every
// `half_period_scans` scans while the module is healthy, for a watchdog relay board. No line: no
// charge pump.
struct ChargePumpSection {
  std::optional<unsigned> line;
  gpio::LineOptions line_opt;
  unsigned frequency_hz = static_cast<unsigned>(config_key("charge_pump", "frequency_hz").def);
  unsigned half_period_scans = 0;  // set by the parser: 1e6 / (2 frequency_hz scan_us)
};

// Initial values: as AxisSection's.
struct Config {
  std::string file;  // the path it was read from
  ModuleType type = ModuleType::k3601;
  std::string name{config_key("module", "name").text};
  Nanos scan_ns = default_ns(config_key("module", "scan_us"));
  Nanos plc_timeout_ns = default_ns(config_key("module", "plc_timeout_ms"));  // 0: watch off
  enum class Backend { kSim, kGpiod } backend{};  // the parser sets it from [gpio] backend
  std::string chip{config_key("gpio", "chip").text};
  int rt_priority = static_cast<int>(config_key("rt", "priority").def);
  int rt_cpu = static_cast<int>(config_key("rt", "cpu").def);  // -1: not pinned
  // Late-edge guard: a pause in an axis' step train longer than this faults the axis at any
  // speed (rt::PulseEngine::set_late_limit; docs/slip.md).
  Nanos late_limit_ns = default_ns(config_key("rt", "late_limit_us"));
  // The line of the file's [rt] table, 0 when it has none (a rack's module file must not have
  // one: config/rack_config.hpp).
  unsigned rt_table_line = 0;
  std::vector<AxisSection> axes;
  ipc::ModbusOptions modbus;  // [modbus] (docs/interface.md 6), every field set by the parser
  enip::AdapterOptions ethernetip;  // [ethernetip] (docs/ethernetip-design.md), the same
  ChargePumpSection charge_pump;
};

// Thrown for a bad file: what() is the whole message ("FILE:LINE: key 'axis[1].step': ...").
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

Config load_config(const std::string& path);  // throws ConfigError
std::string read_config_file(const std::string& path);  // the text; throws ConfigError
Config parse_config(std::string_view toml_text, const std::string& file_name);  // same checks

}  // namespace stepmod::tools

#pragma once
// The daemon's configuration file (INTERFACE.md section 2), parsed and validated. A bad file is
// reported with the file, the key, the problem and the line, and nothing is started.
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpio/backend.hpp"
#include "module/personality.hpp"
#include "rt/clock.hpp"

namespace stepmod::tools {

struct SimAxisConfig {
  std::int64_t start_position = 0;
  std::optional<std::int64_t> cw_limit_at;   // absent: never actuated
  std::optional<std::int64_t> ccw_limit_at;
  std::optional<std::int64_t> home_from;     // home switch actuated in [home_from, home_to]
  std::optional<std::int64_t> home_to;
  bool contacts_nc = false;                  // "NO" (false) or "NC" (true)
  double encoder_ratio = 1.0;                // X4 counts per step; 0 = no encoder signals
  std::optional<std::int64_t> marker_every;  // Z pulse period in encoder counts
};

struct AxisConfig {
  // Line offsets on the chip; absent = not wired (outputs step and dir are required).
  std::optional<unsigned> out[gpio::kOutputLinesPerAxis];  // indexed by rt::OutputLine
  std::optional<unsigned> in[gpio::kInputLinesPerAxis];    // indexed by gpio::InputLine
  Nanos step_pulse_ns = 2'000;
  Nanos dir_setup_ns = 5'000;
  SimAxisConfig sim;
};

struct Config {
  std::string file;  // the path it was read from
  module::ModuleType type = module::ModuleType::k3601;
  std::string name = "stepmod";
  Nanos scan_ns = 1'000 * kNsPerUs;
  Nanos plc_timeout_ns = 0;  // 0 = heartbeat watch off
  enum class Backend { kSim, kGpiod } backend = Backend::kSim;
  std::string chip = "gpiochip0";
  int rt_priority = 80;
  int rt_cpu = -1;
  std::vector<AxisConfig> axes;
};

// Thrown for a bad file: what() is the whole message ("FILE:LINE: key 'axis[1].step': ...").
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

Config load_config(const std::string& path);              // throws ConfigError
Config parse_config(std::string_view toml_text, const std::string& file_name);  // same checks

}  // namespace stepmod::tools

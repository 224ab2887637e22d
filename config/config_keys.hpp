#pragma once
// Every key the configuration file accepts, one row each: its type, default, range, unit, off
// value and meaning. The one place these are stated: the parser (config/config.cpp) takes every
// default and range from here, and so do the Config structs' initial values; a test checks that
// docs/interface.md's key table, the stepmod.toml(5) man page and the examples' commented-out
// defaults state exactly these (tests/tools/config_defaults_doc_test.cpp), and that those two
// list exactly these keys (config_keys_doc_test.cpp). Change a default or a range here, and the
// suite names each document that still states the old one.
#include <array>
#include <cstdint>
#include <iterator>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/clock.hpp"
#include "gpio/sim_machine.hpp"

namespace stepmod::tools {

enum class KeyType : std::uint8_t {
  kTable,   // a sub-table ([module], [axis.sim]), not a value
  kInt,     // an integer, min … max
  kNumber,  // a number (float or integer), min … max; its default `def`
  kBool,    // def: 0 false, 1 true
  kText,    // a string the parser checks itself; min … max: its length where max > 0
  kChoice,  // one of `choices`; its default `text`
  kLine,    // a line offset min … max, or a line table with it (kLineOptionKeys)
  kList,    // an array (of `choices`, where given); its default `text`
};

// What a key left out of the file means.
enum class Absent : std::uint8_t {
  kDefault,   // its default: `def` (kInt, kNumber, kBool) or `text`
  kRequired,  // an error
  kUnset,     // nothing (not wired, never actuated, ...): `text` says what, in the docs' words
};

// The unit of an integer key: a time key's name ends in it (_ns, _us, _ms).
enum class Unit : std::uint8_t { kNone, kNs, kUs, kMs, kSteps };

inline constexpr std::int64_t kUnbounded = std::numeric_limits<std::int64_t>::max();

struct ConfigKey {
  std::string_view table{};  // "" = the file's top level; "axis.sim" = [axis.sim] of an [[axis]]
  std::string_view key{};
  KeyType type = KeyType::kTable;
  Absent absent = Absent::kDefault;
  std::int64_t def = 0;
  std::int64_t min = 0;
  std::int64_t max = 0;  // kUnbounded: no upper bound
  Unit unit = Unit::kNone;
  // The one value that switches the key's function off, where it has one; the docs write it
  // "VALUE (off".
  std::optional<std::int64_t> off{};
  std::string_view text{};  // see Absent and KeyType
  std::array<std::string_view, 4> choices{};
  std::string_view doc{};  // the meaning, as docs/interface.md's key table gives it (Markdown)
};

// Highest line offset accepted. gpiochips have at most a few hundred lines; the bound only
// catches nonsense such as a pin number typed as a physical header position * 1000.
inline constexpr std::int64_t kMaxLineOffset = 4095;
// [axis.sim] positions: far beyond any machine (a trillion steps), small enough that
// position * encoder_ratio stays exact in a double and the step count never overflows.
inline constexpr std::int64_t kMaxSimPosition = 1'000'000'000'000;

namespace config_key_rows {
using enum KeyType;
using enum Absent;
using enum Unit;

constexpr ConfigKey table(std::string_view parent, std::string_view name) {
  return {.table = parent, .key = name};
}
// An [[axis]] line key.
constexpr ConfigKey line(std::string_view name, Absent absent, std::string_view doc) {
  return {.table = "axis",
          .key = name,
          .type = kLine,
          .absent = absent,
          .min = 0,
          .max = kMaxLineOffset,
          .text = absent == kUnset ? "not wired" : "",
          .doc = doc};
}
// An [axis.sim] position that is never reached when left out.
constexpr ConfigKey sim_position(std::string_view name, std::string_view doc) {
  return {.table = "axis.sim",
          .key = name,
          .type = kInt,
          .absent = kUnset,
          .min = -kMaxSimPosition,
          .max = kMaxSimPosition,
          .unit = kSteps,
          .text = "never",
          .doc = doc};
}

// The rows, table by table (an unknown key's message lists its table's keys in this order). Why
// a default or a bound is what it is: the comment above its row. (Not clang-formatted: one row
// per key reads as a table.)
// clang-format off
inline constexpr ConfigKey kConfigKeys[] = {
    table("", "module"),
    table("", "gpio"),
    table("", "rt"),
    table("", "axis"),
    table("", "modbus"),
    table("", "ethernetip"),
    table("", "charge_pump"),
    // [module]
    {.table = "module", .key = "type", .type = kChoice, .absent = kRequired,
     .choices = {"3601", "3602", "3202"},
     .doc = "the emulated module, a string in quotes (a bare integer is refused)"},
    // At most 64 characters: it names /dev/shm/stepmod.NAME.
    {.table = "module", .key = "name", .type = kText, .min = 1, .max = 64, .text = "stepmod",
     .doc = "names the image `/dev/shm/stepmod.NAME` (`stepmodctl -n NAME`)"},
    {.table = "module", .key = "scan_us", .type = kInt, .def = 1000, .min = 250, .max = 100'000,
     .unit = kUs, .doc = "I/O scan period in µs (the module's RPI)"},
    // Up to an hour: more is surely a unit mistake, and would make the watch useless.
    {.table = "module", .key = "plc_timeout_ms", .type = kInt, .def = 0, .min = 0,
     .max = 3'600'000, .unit = kMs, .off = 0,
     .doc = "PLC heartbeat watch (section 3.2): a heartbeat unchanged this long stops every axis "
            "as a PLC leaving Run mode"},
    // [gpio]
    {.table = "gpio", .key = "backend", .type = kChoice, .text = "sim",
     .choices = {"sim", "gpiod"}, .doc = "the built-in simulated machine, or a real gpiochip"},
    {.table = "gpio", .key = "chip", .type = kText, .min = 1, .text = "gpiochip0",
     .doc = "the chip of the gpiod backend"},
    // [rt]
    {.table = "rt", .key = "priority", .type = kInt, .def = 80, .min = 1, .max = 99,
     .doc = "SCHED_FIFO priority of the pulse thread (the control thread runs 10 below)"},
    {.table = "rt", .key = "cpu", .type = kInt, .def = -1, .min = -1, .max = 1023, .off = -1,
     .doc = "CPU the pulse thread is pinned to"},
    // The longest pause at any speed (late edges slip, never burst: docs/slip.md): longer than a
    // stock kernel's 50 ms fair-server / RT-throttling pause, short enough that a stalled board
    // stops its axes within a fraction of a second. No "off" in the file.
    {.table = "rt", .key = "late_limit_us", .type = kInt, .def = 200'000, .min = 20,
     .max = 1'000'000, .unit = kUs,
     .doc = "the longest single pause of a step train, at any speed: a longer one stops the axis "
            "(immediate stop, Position Invalid, health bit 0); shorter pauses slip the motion "
            "(see \"Late edges\")"},
    // [[axis]]
    line("step", kRequired, "line offset: step (or CW pulse) output"),
    line("dir", kRequired, "direction (or CCW pulse) output"),
    line("gpo", kUnset, "3602 only: general-purpose output"),
    line("capture", kUnset, "input: capture"),
    line("external", kUnset, "input: external"),
    line("home", kUnset, "input: home switch"),
    line("estop", kUnset, "3601 and 3202 only: input E-stop"),
    line("cw_limit", kUnset,
         "input: CW limit (3602: the CW input, limit or E-stop by configuration)"),
    line("ccw_limit", kUnset, "input: CCW limit (3602: the CCW input)"),
    line("enc_a", kUnset, "3601 and 3202 only: encoder phase A (with `enc_b`)"),
    line("enc_b", kUnset, "3601 and 3202 only: encoder phase B (with `enc_a`)"),
    line("enc_z", kUnset, "3601 and 3202 only: encoder marker"),
    {.table = "axis", .key = "step_pulse_ns", .type = kInt, .def = 2'000, .min = 100,
     .max = 1'000'000, .unit = kNs,
     .doc = "width of a step pulse; shortened to half the step period where it would not fit"},
    {.table = "axis", .key = "dir_setup_ns", .type = kInt, .def = 5'000, .min = 1,
     .max = 1'000'000, .unit = kNs, .doc = "direction edge → next step edge"},
    // A motor bridges 1-2 full steps of lag, m..2m output steps at m microsteps: one full step at
    // 8 microsteps (docs/slip.md).
    {.table = "axis", .key = "lag_limit_steps", .type = kInt, .def = 8, .min = 1,
     .max = 1'000'000, .unit = kSteps,
     .doc = "output steps the axis may lag behind its plan after a pause while above its "
            "starting speed Vs; more is a fault (see \"Late edges\"; the default is one full step "
            "at 8 microsteps)"},
    line("enable", kUnset,
         "extension: the drive's enable (ENA) output, asserted while the axis is configured and "
         "the module is OK; polarity by `active_low` ([gpio-boards.md](gpio-boards.md))"),
    {.table = "axis", .key = "enable_delay_us", .type = kInt, .def = 10'000, .min = 0,
     .max = 10'000'000, .unit = kUs,
     .doc = "with `enable`: commands wait this long after the enable is asserted (the drive gets "
            "ready)"},
    // Empty: a released drive drops its holding torque, and a vertical axis falls.
    {.table = "axis", .key = "enable_release_on", .type = kList, .text = "[]",
     .choices = {"estop", "fault", "plc_loss", "config_mode"},
     .doc = "with `enable`: conditions that release the drive (a released drive drops its "
            "holding torque: a vertical axis falls)"},
    table("axis", "sim"),
    // [axis.sim]
    {.table = "axis.sim", .key = "start_position", .type = kInt, .def = 0,
     .min = -kMaxSimPosition, .max = kMaxSimPosition, .unit = kSteps,
     .doc = "simulated motor position at start-up (steps)"},
    sim_position("cw_limit_at", "CW limit actuated while position ≥ this"),
    sim_position("ccw_limit_at", "CCW limit actuated while position ≤ this"),
    sim_position("home_from", "home actuated while `home_from` ≤ position ≤ `home_to`"),
    sim_position("home_to", "see `home_from`"),
    {.table = "axis.sim", .key = "contacts", .type = kChoice, .text = "NO",
     .choices = {"NO", "NC"}, .doc = "NO: an actuated switch drives its line high; NC: low"},
    // The simulated motor emits |ratio| encoder counts per step from the pulse thread's line
    // write, one at a time; a real encoder/motor pair is well below 1000 (a 2500-line encoder on
    // a 200-step motor: 50), and a huge value would stall the pulse thread.
    {.table = "axis.sim", .key = "encoder_ratio", .type = kNumber, .def = 1, .min = -1000,
     .max = 1000, .doc = "X4 encoder counts per motor step (sign = direction; 0 = no encoder)"},
    {.table = "axis.sim", .key = "marker_every", .type = kInt, .absent = kUnset, .min = 1,
     .max = kUnbounded, .text = "no marker",
     .doc = "one Z pulse each time the encoder count is a multiple of this"},
    // A power of two (SpscRing); why the default is what it is: gpio/sim_machine.hpp.
    {.table = "axis.sim", .key = "event_ring", .type = kInt,
     .def = static_cast<std::int64_t>(gpio::kDefaultSimEventRing), .min = 2, .max = 1 << 20,
     .doc = "the simulated machine's input-event queue; an overflow is a lost event (health bit "
            "5)"},
    // [modbus] (docs/interface.md section 6)
    {.table = "modbus", .key = "enabled", .type = kBool, .def = 0,
     .doc = "true: serve the image over Modbus/TCP (section 6)"},
    // Loopback: Modbus has no authentication, so binding anywhere else must be written out.
    {.table = "modbus", .key = "listen", .type = kText, .text = "127.0.0.1:1502",
     .doc = "bind elsewhere only on purpose: Modbus has no authentication"},
    {.table = "modbus", .key = "unit_id", .type = kInt, .def = 1, .min = 0, .max = 255,
     .doc = "a request for another unit gets exception 0B"},
    {.table = "modbus", .key = "writes", .type = kBool, .def = 0,
     .doc = "true: a master may write the output words (it then is the PLC)"},
    {.table = "modbus", .key = "max_clients", .type = kInt, .def = 4, .min = 1, .max = 64,
     .doc = "a new connection beyond it closes the longest-idle one (one that has asked nothing "
            "first), so idle sockets cannot keep the PLC out (docs/hardening.md)"},
    // Up to an hour: longer would let idle sockets hold their places all but for ever.
    {.table = "modbus", .key = "idle_timeout_ms", .type = kInt, .def = 5000, .min = 100,
     .max = 3'600'000, .unit = kMs,
     .doc = "a connection nothing has come from for this long is closed; set it above the "
            "slowest master's poll period"},
    {.table = "modbus", .key = "allow", .type = kList, .absent = kUnset, .text = "any source",
     .doc = "a connection from elsewhere is closed at once (docs/hardening.md)"},
    // [ethernetip] (docs/ethernetip-design.md): an extension, off by default.
    {.table = "ethernetip", .key = "enabled", .type = kBool, .def = 0,
     .doc = "true: serve the image as an EtherNet/IP adapter (class 1 I/O for a Logix PLC)"},
    // Loopback, as Modbus: an EtherNet/IP adapter has no authentication either.
    {.table = "ethernetip", .key = "listen", .type = kText, .text = "127.0.0.1:44818",
     .doc = "TCP and UDP encapsulation; class 1 I/O on UDP 2222 of the same address; in a rack "
            "one address per module"},
    {.table = "ethernetip", .key = "allow", .type = kList, .absent = kUnset, .text = "any source",
     .doc = "originator addresses allowed; a connection, request or I/O packet from elsewhere is "
            "dropped"},
    // Defaults: 1 ms, a Logix PLC's shortest usual RPI; 100 ms, beyond which a silent PLC
    // stops a move late (the timeout is RPI x the multiplier). The bounds: 250 us, the shortest
    // scan_us (faster I/O than the module scans is useless); 10 s. The ranges meet at 1 ms ..
    // 100 ms so that each bound is valid with the other key's default.
    {.table = "ethernetip", .key = "rpi_min_us", .type = kInt, .def = 1000, .min = 250,
     .max = 100'000, .unit = kUs,
     .doc = "the shortest requested packet interval accepted (Forward_Open 0x01/0x0112 below)"},
    {.table = "ethernetip", .key = "rpi_max_us", .type = kInt, .def = 100'000, .min = 1000,
     .max = 10'000'000, .unit = kUs,
     .doc = "the longest requested packet interval accepted; at least `rpi_min_us`"},
    // [charge_pump] (docs/safety.md "Charge pump"): an extension, off unless `line` names a line.
    {.table = "charge_pump", .key = "line", .type = kLine, .absent = kUnset, .min = 0,
     .max = kMaxLineOffset, .text = "not wired",
     .doc = "extension: the charge-pump (watchdog) output, a square wave while the module is "
            "healthy and scanning, for a relay board in the E-stop chain "
            "([safety.md](safety.md))"},
    // 100 Hz: a half period of 5 scans at the default scan_us, well inside what a retriggerable
    // monostable relay board is set for (tens of ms). At least 10 Hz: slower would need a
    // drop-out time so long that the chain opened late; at most 2000 Hz: one scan per half period
    // at the shortest scan_us (250 us).
    {.table = "charge_pump", .key = "frequency_hz", .type = kInt, .def = 100, .min = 10,
     .max = 2000,
     .doc = "with `line`: the square wave's frequency; its half period must be a whole number of "
            "scans (`module.scan_us`)"},
};

// clang-format on

// The options of a line table (`home = { offset = 13, bias = "pull-up" }`), for inputs and
// outputs alike (config/config.cpp lists which direction takes which; docs/gpio-boards.md).
// clang-format off
inline constexpr ConfigKey kLineOptionKeys[] = {
    {.table = "line", .key = "offset", .type = kInt, .absent = kRequired, .min = 0,
     .max = kMaxLineOffset},
    {.table = "line", .key = "active_low", .type = kBool, .def = 0},
    {.table = "line", .key = "bias", .type = kChoice, .text = "as-is",
     .choices = {"as-is", "pull-up", "pull-down", "disabled"}},
    {.table = "line", .key = "debounce_us", .type = kInt, .def = 0, .min = 0, .max = 1'000'000,
     .unit = kUs, .off = 0},
    {.table = "line", .key = "drive", .type = kChoice, .text = "push-pull",
     .choices = {"push-pull", "open-drain", "open-source"}},
};
// clang-format on
}  // namespace config_key_rows

using config_key_rows::kConfigKeys;

// A rack file's own keys (docs/interface.md section 7): [rack] modules; its [rt] table takes the
// rows of kConfigKeys' [rt]. A rack file has no other table.
// clang-format off
inline constexpr ConfigKey kRackModulesKey = {
    .table = "rack", .key = "modules", .type = KeyType::kList, .absent = Absent::kRequired,
    .min = 1, .max = 16,
    .doc = "the module files (section 2) of the rack, absolute or relative to the rack file"};
// clang-format on
using config_key_rows::kLineOptionKeys;

// The row of `table`.`key` (the line options: table "line"), or null.
constexpr const ConfigKey* find_config_key(std::string_view table, std::string_view key) {
  for (const ConfigKey& k : kConfigKeys) {
    if (k.table == table && k.key == key) return &k;
  }
  for (const ConfigKey& k : kLineOptionKeys) {
    if (k.table == table && k.key == key) return &k;
  }
  return nullptr;
}

// The row of `table`.`key`, found at compile time: a key that is not in the table does not
// compile. (Plain strings: a reference returned for class temporaries would be a
// -Wdangling-reference false alarm of newer compilers.)
// (By index, not pointer: GCC's -fsanitize=undefined makes a compared pointer into the table
// no constant expression, and the sanitizer builds would not compile.)
consteval const ConfigKey& config_key(const char* table, const char* key) {
  const std::string_view t{table};
  const std::string_view k{key};
  for (std::size_t i = 0; i < std::size(kConfigKeys); ++i) {
    if (kConfigKeys[i].table == t && kConfigKeys[i].key == k) return kConfigKeys[i];
  }
  for (std::size_t i = 0; i < std::size(kLineOptionKeys); ++i) {
    if (kLineOptionKeys[i].table == t && kLineOptionKeys[i].key == k) return kLineOptionKeys[i];
  }
  throw "config/config_keys.hpp has no such key";
}

constexpr Nanos unit_ns(Unit u) {
  return u == Unit::kUs ? kNsPerUs : u == Unit::kMs ? kNsPerMs : 1;
}

// A time key's default in nanoseconds.
constexpr Nanos default_ns(const ConfigKey& k) {
  return k.def * unit_ns(k.unit);
}

// The keys allowed directly in `table` (values and sub-tables), in the order above.
inline std::vector<std::string_view> config_keys_of(std::string_view table) {
  std::vector<std::string_view> keys;
  for (const ConfigKey& k : kConfigKeys) {
    if (k.table == table) keys.push_back(k.key);
  }
  return keys;
}

// A value key as the docs write it: "module.type", "axis.sim.home_from".
inline std::string config_key_name(const ConfigKey& k) {
  return std::string(k.table) + "." + std::string(k.key);
}

// Every value key as the docs write it.
inline std::vector<std::string> config_value_key_names() {
  std::vector<std::string> names;
  for (const ConfigKey& k : kConfigKeys) {
    if (k.type != KeyType::kTable) names.push_back(config_key_name(k));
  }
  return names;
}

}  // namespace stepmod::tools

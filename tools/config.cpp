// The configuration file of INTERFACE.md section 2. Strict by design: an unknown key is an
// error, because a misspelt key would otherwise silently fall back to its default and the daemon
// would drive the machine with a setting the user did not write.
#include "tools/config.hpp"

#include <arpa/inet.h>
#include <toml++/toml.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <map>
#include <sstream>
#include <string_view>

#include "gpio/sim_machine.hpp"
#include "tools/config_keys.hpp"

namespace stepmod::tools {
namespace {

using std::int64_t;

// Highest line offset accepted. gpiochips have at most a few hundred lines; the bound only
// catches nonsense such as a pin number typed as a physical header position * 1000.
constexpr int64_t kMaxLineOffset = 4095;

// [axis.sim] bounds. Positions: far beyond any machine (a trillion steps), small enough that
// position * encoder_ratio stays exact in a double and the step count never overflows.
// encoder_ratio: the simulated motor emits |ratio| encoder counts per step from the pulse
// thread's line write, one at a time; a real encoder/motor pair is well below 1000 (a
// 2500-line encoder on a 200-step motor: 50), and a huge value would stall the pulse thread.
constexpr int64_t kMaxSimPosition = 1'000'000'000'000;
constexpr double kMaxEncoderRatio = 1000.0;

constexpr std::string_view kOutputKeys[kOutputLinesPerAxis] = {"step", "dir", "gpo"};
constexpr std::string_view kInputKeys[kInputLinesPerAxis] = {
    "capture", "external", "home", "estop", "cw_limit", "ccw_limit", "enc_a", "enc_b", "enc_z"};

class Parser {
 public:
  explicit Parser(std::string file) : file_(std::move(file)) {}

  Config run(std::string_view text) {
    toml::table root;
    try {
      root = toml::parse(text, file_);
    } catch (const toml::parse_error& e) {
      throw ConfigError(file_ + ":" + std::to_string(e.source().begin.line) +
                        ": TOML syntax error: " + std::string(e.description()));
    }
    Config c;
    c.file = file_;
    check_keys(root, "", "");

    const toml::table* module = sub_table(root, "", "module");
    parse_module(module, c);
    parse_gpio(sub_table(root, "", "gpio"), c);
    parse_rt(sub_table(root, "", "rt"), c);
    parse_axes(root, module, c);
    parse_modbus(sub_table(root, "", "modbus"), c);
    return c;
  }

 private:
  [[noreturn]] void fail(const toml::source_region& where, const std::string& key,
                         const std::string& what) const {
    std::string loc = file_;
    if (where.begin.line > 0) loc += ":" + std::to_string(where.begin.line);
    throw ConfigError(loc + ": key '" + key + "': " + what);
  }

  static std::string join(const std::string& prefix, std::string_view key) {
    return prefix.empty() ? std::string(key) : prefix + "." + std::string(key);
  }

  // `table` names the table in kConfigKeys ("axis.sim"); `prefix` is how the message names it
  // ("axis[1].sim").
  void check_keys(const toml::table& t, const std::string& prefix, std::string_view table) const {
    check_keys_in(t, prefix, config_keys_of(table));
  }

  // An inline line table's options (`home = { offset = 13, bias = "pull-up" }`): their own short
  // lists, per direction (docs/gpio-boards.md), not rows of kConfigKeys.
  void check_keys(const toml::table& t, const std::string& prefix,
                  std::initializer_list<std::string_view> allowed) const {
    check_keys_in(t, prefix, std::vector<std::string_view>(allowed));
  }

  void check_keys_in(const toml::table& t, const std::string& prefix,
                     const std::vector<std::string_view>& allowed) const {
    for (auto&& [k, v] : t) {
      bool ok = false;
      for (std::string_view a : allowed) ok = ok || k.str() == a;
      if (!ok) {
        std::string list;
        for (std::string_view a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
        fail(k.source(), join(prefix, k.str()), "unknown key (expected one of: " + list + ")");
      }
    }
  }

  // A [table] that may be absent (all defaults); anything else under that name is an error.
  const toml::table* sub_table(const toml::table& t, const std::string& prefix,
                               std::string_view key) const {
    const toml::node* n = t.get(key);
    if (n == nullptr) return nullptr;
    if (!n->is_table())
      fail(n->source(), join(prefix, key), "must be a table [" + join(prefix, key) + "]");
    return n->as_table();
  }

  static std::string range_text(int64_t lo, int64_t hi) {
    if (lo == std::numeric_limits<int64_t>::min() && hi == std::numeric_limits<int64_t>::max()) {
      return "must be an integer";
    }
    if (hi == std::numeric_limits<int64_t>::max()) {
      return "must be an integer >= " + std::to_string(lo);
    }
    return "must be an integer " + std::to_string(lo) + ".." + std::to_string(hi);
  }

  std::optional<int64_t> opt_int(const toml::table* t, const std::string& prefix,
                                 std::string_view key,
                                 int64_t lo = std::numeric_limits<int64_t>::min(),
                                 int64_t hi = std::numeric_limits<int64_t>::max()) const {
    if (t == nullptr) return std::nullopt;
    const toml::node* n = t->get(key);
    if (n == nullptr) return std::nullopt;
    const auto* v = n->as_integer();
    if (v == nullptr || v->get() < lo || v->get() > hi) {
      fail(n->source(), join(prefix, key), range_text(lo, hi));
    }
    return v->get();
  }

  int64_t get_int(const toml::table* t, const std::string& prefix, std::string_view key,
                  int64_t def, int64_t lo = std::numeric_limits<int64_t>::min(),
                  int64_t hi = std::numeric_limits<int64_t>::max()) const {
    return opt_int(t, prefix, key, lo, hi).value_or(def);
  }

  // A string limited to `choices`; `def` when absent.
  std::string get_choice(const toml::table* t, const std::string& prefix, std::string_view key,
                         std::initializer_list<std::string_view> choices,
                         std::string_view def) const {
    if (t == nullptr) return std::string(def);
    const toml::node* n = t->get(key);
    if (n == nullptr) return std::string(def);
    const auto* s = n->as_string();
    for (std::string_view c : choices) {
      if (s != nullptr && s->get() == c) return s->get();
    }
    std::string list;
    for (std::string_view c : choices) {
      list += (list.empty() ? "\"" : ", \"") + std::string(c) + "\"";
    }
    fail(n->source(), join(prefix, key), "must be one of " + list);
  }

  bool get_bool(const toml::table* t, const std::string& prefix, std::string_view key,
                bool def) const {
    if (t == nullptr) return def;
    const toml::node* n = t->get(key);
    if (n == nullptr) return def;
    const auto* b = n->as_boolean();
    if (b == nullptr) fail(n->source(), join(prefix, key), "must be true or false");
    return b->get();
  }

  // [modbus] (INTERFACE.md 6). `listen` is a numeric IPv4 address and a port: Modbus has no
  // authentication, so binding anywhere but loopback must be written out on purpose.
  void parse_modbus(const toml::table* t, Config& c) const {
    const std::string p = "modbus";
    if (t == nullptr) return;
    check_keys(*t, p, "modbus");
    ipc::ModbusOptions& m = c.modbus;
    m.enabled = get_bool(t, p, "enabled", false);
    m.writes = get_bool(t, p, "writes", false);
    m.unit_id = static_cast<std::uint8_t>(get_int(t, p, "unit_id", 1, 0, 255));
    m.max_clients = static_cast<unsigned>(get_int(t, p, "max_clients", 4, 1, 64));
    // Up to an hour: longer would let idle sockets hold their places all but for ever.
    m.idle_timeout_ms =
        static_cast<unsigned>(get_int(t, p, "idle_timeout_ms", 5000, 100, 3'600'000));
    if (const toml::node* n = t->get("listen")) {
      const auto* s = n->as_string();
      const std::string text = s != nullptr ? s->get() : std::string();
      const auto colon = text.rfind(':');
      in_addr addr{};
      bool ok = colon != std::string::npos && colon > 0 &&
                ::inet_pton(AF_INET, text.substr(0, colon).c_str(), &addr) == 1;
      long port = 0;
      if (ok) {
        const std::string ps = text.substr(colon + 1);
        ok = !ps.empty() && ps.size() <= 5 &&
             ps.find_first_not_of("0123456789") == std::string::npos;
        if (ok) port = std::stol(ps);
        ok = ok && port >= 1 && port <= 65535;
      }
      if (!ok) {
        fail(n->source(), "modbus.listen",
             "must be \"IPv4-ADDRESS:PORT\" with a port 1..65535, e.g. \"127.0.0.1:1502\"");
      }
      m.address = text.substr(0, colon);
      m.port = static_cast<std::uint16_t>(port);
    }
    parse_modbus_allow(t, m);
  }

  // [modbus] allow = ["127.0.0.1", "10.0.0.0/8", ...]: where connections may come from.
  void parse_modbus_allow(const toml::table* t, ipc::ModbusOptions& m) const {
    const toml::node* n = t->get("allow");
    if (n == nullptr) return;
    const auto* list = n->as_array();
    if (list == nullptr || list->empty()) {
      fail(n->source(), "modbus.allow",
           "must be a non-empty list of IPv4 addresses or networks, e.g. [\"127.0.0.1\", "
           "\"10.0.0.0/8\"]");
    }
    for (const toml::node& e : *list) {
      const auto* s = e.as_string();
      const auto net = s != nullptr ? ipc::parse_allow_net(s->get()) : std::nullopt;
      if (!net) {
        fail(e.source(), "modbus.allow",
             "each entry must be an IPv4 address or ADDRESS/PREFIX (0..32) in quotes, e.g. "
             "\"10.0.0.0/8\"");
      }
      m.allow.push_back(*net);
    }
  }

  void parse_module(const toml::table* m, Config& c) const {
    const std::string p = "module";
    if (m != nullptr) check_keys(*m, p, "module");
    const toml::node* type = m != nullptr ? m->get("type") : nullptr;
    if (type == nullptr) {
      toml::source_region where{};
      if (m != nullptr) where = m->source();
      fail(where, "module.type", "required: \"3601\", \"3602\" or \"3202\"");
    }
    // A string, as the contract writes it: a bare 3602 is refused like every other mistyped
    // value (one spelling, so that scripts and the docs agree).
    std::string ts;
    if (const auto* s = type->as_string()) ts = s->get();
    if (type->as_integer() != nullptr) {
      fail(type->source(), "module.type",
           "must be a string in quotes: type = \"" + std::to_string(type->as_integer()->get()) +
               "\"");
    }
    if (const auto t = module_type_from_name(ts)) {
      c.type = *t;
    } else {
      fail(type->source(), "module.type", "must be \"3601\", \"3602\" or \"3202\"");
    }

    if (const toml::node* n = m->get("name")) {
      const auto* s = n->as_string();
      bool ok = s != nullptr && !s->get().empty() && s->get().size() <= 64;
      if (ok) {
        for (char ch : s->get()) {
          ok = ok &&
               ((ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '-' || ch == '_');
        }
      }
      if (!ok) {
        fail(n->source(), "module.name",
             "must be 1..64 characters of a-z, 0-9, '-' and '_' (it names /dev/shm/stepmod.NAME)");
      }
      c.name = s->get();
    }
    c.scan_ns = get_int(m, p, "scan_us", 1000, 250, 100'000) * kNsPerUs;
    // Upper bound: an hour; larger values are surely a unit mistake and would overflow nothing,
    // but would make the watch useless.
    c.plc_timeout_ns = get_int(m, p, "plc_timeout_ms", 0, 0, 3'600'000) * kNsPerMs;
  }

  void parse_gpio(const toml::table* g, Config& c) const {
    const std::string p = "gpio";
    if (g == nullptr) return;
    check_keys(*g, p, "gpio");
    c.backend = get_choice(g, p, "backend", {"sim", "gpiod"}, "sim") == "gpiod"
                    ? Config::Backend::kGpiod
                    : Config::Backend::kSim;
    if (const toml::node* n = g->get("chip")) {
      const auto* s = n->as_string();
      if (s == nullptr || s->get().empty()) {
        fail(n->source(), "gpio.chip", "must be a chip name (gpiochip0) or a /dev path");
      }
      c.chip = s->get();
    }
  }

  void parse_rt(const toml::table* r, Config& c) const {
    const std::string p = "rt";
    if (r == nullptr) return;
    check_keys(*r, p, "rt");
    c.rt_priority = static_cast<int>(get_int(r, p, "priority", 80, 1, 99));
    c.rt_cpu = static_cast<int>(get_int(r, p, "cpu", -1, -1, 1023));
    // The longest pause at any speed (late edges slip, never burst: docs/slip.md). 200 ms:
    // longer than a stock kernel's 50 ms fair-server / RT-throttling pause, short enough that a
    // stalled board stops its axes within a fraction of a second. No "off".
    c.late_limit_ns = get_int(r, p, "late_limit_us", 200'000, 20, 1'000'000) * kNsPerUs;
  }

  void parse_axes(const toml::table& root, const toml::table* module, Config& c) const {
    const unsigned shape = shape_of(c.type).axes;
    const toml::node* n = root.get("axis");
    const toml::array* arr = nullptr;
    if (n != nullptr) {
      arr = n->as_array();
      if (arr == nullptr || !arr->is_array_of_tables()) {
        fail(n->source(), "axis", "must be [[axis]] tables");
      }
    }
    const std::size_t count = arr != nullptr ? arr->size() : 0;
    if (count != shape) {
      toml::source_region where{};
      if (arr != nullptr && count > 0) {
        where = (*arr)[count - 1].source();
      } else if (module != nullptr) {
        where = module->source();
      }
      fail(where, "axis",
           "module type " + std::to_string(static_cast<unsigned>(c.type)) + " needs exactly " +
               std::to_string(shape) + " [[axis]] table" + (shape == 1 ? "" : "s") + ", found " +
               std::to_string(count));
    }
    // Line offset -> key that uses it, for the uniqueness check across the whole file.
    std::map<int64_t, std::string> used;
    for (std::size_t i = 0; i < count; ++i) {
      c.axes.push_back(
          parse_axis(*(*arr)[i].as_table(), i, c.type, c.backend == Config::Backend::kGpiod, used));
    }
  }

  AxisConfig parse_axis(const toml::table& t, std::size_t index, ModuleType type, bool gpiod,
                        std::map<int64_t, std::string>& used) const {
    // 1-based like the contract's "axis 1, then axis 2" and the VCD names axis1.step.
    const std::string p = "axis[" + std::to_string(index + 1) + "]";
    check_keys(t, p, "axis");
    AxisConfig a;
    auto line = [&](std::string_view key, bool input,
                    gpio::LineOptions& opt) -> std::optional<unsigned> {
      const auto v = line_entry(t, p, key, input, gpiod, opt);
      if (!v) return std::nullopt;
      const auto [it, fresh] = used.emplace(*v, join(p, key));
      if (!fresh) {
        fail(t.get(key)->source(), join(p, key),
             "line offset " + std::to_string(*v) + " is already used by '" + it->second + "'");
      }
      return static_cast<unsigned>(*v);
    };
    for (unsigned o = 0; o < kOutputLinesPerAxis; ++o) {
      a.out[o] = line(kOutputKeys[o], false, a.out_opt[o]);
    }
    for (unsigned i = 0; i < kInputLinesPerAxis; ++i) {
      a.in[i] = line(kInputKeys[i], true, a.in_opt[i]);
    }
    a.enable = line("enable", false, a.enable_opt);
    parse_enable(t, p, a);

    for (std::string_view req : {"step", "dir"}) {
      if (t.get(req) == nullptr) {
        fail(t.source(), join(p, req),
             "required: the line offset of the " +
                 std::string(req == "step" ? "step (or CW pulse)" : "direction (or CCW pulse)") +
                 " output");
      }
    }
    refuse_absent_terminals(t, p, shape_of(type));
    // A and B only make sense as a pair: one phase alone cannot be decoded.
    if ((t.get("enc_a") == nullptr) != (t.get("enc_b") == nullptr)) {
      const std::string_view present = t.get("enc_a") != nullptr ? "enc_a" : "enc_b";
      fail(t.get(present)->source(), join(p, present),
           "enc_a and enc_b must both be given (quadrature needs both phases)");
    }
    a.step_pulse_ns = get_int(&t, p, "step_pulse_ns", 2'000, 100, 1'000'000);
    a.dir_setup_ns = get_int(&t, p, "dir_setup_ns", 5'000, 1, 1'000'000);
    // Output steps of lag above Vs (docs/slip.md): a motor bridges 1-2 full steps, m..2m
    // microsteps; 8 = one full step at 8 microsteps.
    a.lag_limit_steps =
        static_cast<std::uint32_t>(get_int(&t, p, "lag_limit_steps", 8, 1, 1'000'000));
    a.sim = parse_sim(sub_table(t, p, "sim"), p + ".sim");
    if (!shape_of(type).terminals.encoder) {
      refuse_sim_encoder(sub_table(t, p, "sim"), p + ".sim", type);
    }
    return a;
  }

  // The line keys of terminals the module type has not (core/module_shape.hpp AxisTerminals).
  void refuse_absent_terminals(const toml::table& t, const std::string& p,
                               const ModuleShape& shape) const {
    const std::string name = std::to_string(static_cast<unsigned>(shape.type));
    if (!shape.terminals.gpo && t.get("gpo") != nullptr) {
      std::string owners;  // the types that have one: "3602"
      for (const ModuleShape& s : kModuleShapes) {
        if (!s.terminals.gpo) continue;
        owners += (owners.empty() ? "" : " and ") + std::to_string(static_cast<unsigned>(s.type));
      }
      fail(t.get("gpo")->source(), join(p, "gpo"),
           "only the " + owners + " has a general-purpose output");
    }
    if (!shape.terminals.estop) {
      if (const toml::node* n = t.get("estop")) {
        // Without an E-stop terminal its cw_limit/ccw_limit inputs serve as E-stops (3602).
        fail(n->source(), join(p, "estop"),
             "the " + name +
                 " has no E-stop input (its cw_limit/ccw_limit inputs are configured as limit or "
                 "E-stop by the PLC)");
      }
    }
    if (shape.terminals.encoder) return;
    for (std::string_view k : {"enc_a", "enc_b", "enc_z"}) {
      if (const toml::node* n = t.get(k)) {
        fail(n->source(), join(p, k), "the " + name + " has no encoder input");
      }
    }
  }

  // A line key: its offset (`home = 5`), or the offset with electrical options
  // (`home = { offset = 5, bias = "pull-up", active_low = true, debounce_us = 2000 }`).
  std::optional<int64_t> line_entry(const toml::table& t, const std::string& p,
                                    std::string_view key, bool input, bool gpiod,
                                    gpio::LineOptions& opt) const {
    const toml::node* n = t.get(key);
    if (n == nullptr) return std::nullopt;
    const toml::table* o = n->as_table();
    if (o == nullptr) {
      return opt_int(&t, p, key, 0, kMaxLineOffset);
    }
    const std::string q = join(p, key);
    if (input) {
      check_keys(*o, q, {"offset", "active_low", "bias", "debounce_us"});
    } else {
      check_keys(*o, q, {"offset", "active_low", "drive"});
    }
    const auto off = opt_int(o, q, "offset", 0, kMaxLineOffset);
    if (!off) fail(o->source(), join(q, "offset"), "required: the line offset on the chip");
    opt.active_low = get_bool(o, q, "active_low", false);
    if (input) {
      const std::string b =
          get_choice(o, q, "bias", {"as-is", "pull-up", "pull-down", "disabled"}, "as-is");
      opt.bias = b == "pull-up"     ? gpio::Bias::kPullUp
                 : b == "pull-down" ? gpio::Bias::kPullDown
                 : b == "disabled"  ? gpio::Bias::kDisabled
                                    : gpio::Bias::kAsIs;
      opt.debounce_us = static_cast<std::uint32_t>(get_int(o, q, "debounce_us", 0, 0, 1'000'000));
      if (opt.debounce_us != 0 && gpiod && !gpio::gpiod_capabilities().debounce) {
        fail(o->get("debounce_us")->source(), join(q, "debounce_us"),
             "kernel debounce needs libgpiod 2; this stepmod is built with libgpiod " +
                 std::to_string(gpio::gpiod_capabilities().libgpiod_major) +
                 ".x (v1 uAPI, no debounce): debounce in hardware (RC filter) or remove the key");
      }
    } else {
      const std::string d =
          get_choice(o, q, "drive", {"push-pull", "open-drain", "open-source"}, "push-pull");
      opt.drive = d == "open-drain"    ? gpio::Drive::kOpenDrain
                  : d == "open-source" ? gpio::Drive::kOpenSource
                                       : gpio::Drive::kPushPull;
    }
    return off;
  }

  // The drive-enable output's keys (an extension: off unless `enable` names a line).
  void parse_enable(const toml::table& t, const std::string& p, AxisConfig& a) const {
    if (!a.enable) {
      for (std::string_view k : {"enable_delay_us", "enable_release_on"}) {
        if (const toml::node* n = t.get(k)) {
          fail(n->source(), join(p, k), "needs an enable line (key 'enable')");
        }
      }
      return;
    }
    a.enable_delay_ns = get_int(&t, p, "enable_delay_us", 10'000, 0, 10'000'000) * kNsPerUs;
    const toml::node* n = t.get("enable_release_on");
    if (n == nullptr) return;
    const toml::array* arr = n->as_array();
    const std::string what =
        "must be a list of \"estop\", \"fault\", \"plc_loss\", \"config_mode\" (default [])";
    if (arr == nullptr) fail(n->source(), join(p, "enable_release_on"), what);
    for (const toml::node& e : *arr) {
      const auto* s = e.as_string();
      const std::string v = s != nullptr ? s->get() : "";
      const std::uint8_t bit = v == "estop"         ? kReleaseOnEStop
                               : v == "fault"       ? kReleaseOnFault
                               : v == "plc_loss"    ? kReleaseOnPlcLoss
                               : v == "config_mode" ? kReleaseOnConfigMode
                                                    : 0;
      if (bit == 0) fail(e.source(), join(p, "enable_release_on"), what);
      a.enable_release |= bit;
    }
  }

  // The 3602 has no encoder input: a simulated encoder for it is a config meant for another
  // module (the 3601/3202 examples have one).
  void refuse_sim_encoder(const toml::table* s, const std::string& p, ModuleType type) const {
    if (s == nullptr) return;
    for (std::string_view k : {"encoder_ratio", "marker_every"}) {
      if (const toml::node* n = s->get(k)) {
        fail(n->source(), join(p, k),
             "the " + std::to_string(static_cast<unsigned>(type)) +
                 " has no encoder input: remove this key");
      }
    }
  }

  SimAxisConfig parse_sim(const toml::table* s, const std::string& p) const {
    SimAxisConfig c;
    if (s == nullptr) return c;
    check_keys(*s, p, "axis.sim");
    constexpr int64_t lo = -kMaxSimPosition;
    constexpr int64_t hi = kMaxSimPosition;
    c.start_position = get_int(s, p, "start_position", 0, lo, hi);
    c.cw_limit_at = opt_int(s, p, "cw_limit_at", lo, hi);
    c.ccw_limit_at = opt_int(s, p, "ccw_limit_at", lo, hi);
    if (c.cw_limit_at && c.ccw_limit_at && !(*c.ccw_limit_at < *c.cw_limit_at)) {
      fail(s->get("ccw_limit_at")->source(), join(p, "ccw_limit_at"),
           "must be less than cw_limit_at (" + std::to_string(*c.cw_limit_at) + ")");
    }
    c.home_from = opt_int(s, p, "home_from", lo, hi);
    c.home_to = opt_int(s, p, "home_to", lo, hi);
    if (c.home_from.has_value() != c.home_to.has_value()) {
      const std::string_view present = c.home_from ? "home_from" : "home_to";
      fail(s->get(present)->source(), join(p, present),
           "home_from and home_to must be given together");
    }
    if (c.home_from && *c.home_from > *c.home_to) {
      fail(s->get("home_to")->source(), join(p, "home_to"),
           "must be >= home_from (" + std::to_string(*c.home_from) + ")");
    }
    c.contacts_nc = get_choice(s, p, "contacts", {"NO", "NC"}, "NO") == "NC";
    if (const toml::node* n = s->get("encoder_ratio")) {
      std::optional<double> v;
      if (const auto* f = n->as_floating_point()) v = f->get();
      if (const auto* i = n->as_integer()) v = static_cast<double>(i->get());
      if (!v || !std::isfinite(*v) || std::fabs(*v) > kMaxEncoderRatio) {
        fail(n->source(), join(p, "encoder_ratio"), "must be a finite number, -1000 .. 1000");
      }
      c.encoder_ratio = *v;
    }
    c.marker_every = opt_int(s, p, "marker_every", 1);
    c.event_ring = sim_event_ring(s, p);
    return c;
  }

  // [axis.sim] event_ring: the simulated input event FIFO, a power of two (SpscRing).
  std::size_t sim_event_ring(const toml::table* s, const std::string& p) const {
    const int64_t v = get_int(s, p, "event_ring",
                              static_cast<std::int64_t>(gpio::kDefaultSimEventRing), 2, 1 << 20);
    if ((v & (v - 1)) != 0) {
      fail(s->get("event_ring")->source(), join(p, "event_ring"),
           "must be a power of two, 2 .. 1048576 (default 65536)");
    }
    return static_cast<std::size_t>(v);
  }

  std::string file_;
};

}  // namespace

Config parse_config(std::string_view toml_text, const std::string& file_name) {
  return Parser(file_name).run(toml_text);
}

Config load_config(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(path + ": cannot read: " + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_config(ss.str(), path);
}

}  // namespace stepmod::tools

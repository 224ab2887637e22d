// The configuration file of docs/interface.md section 2. Strict by design: an unknown key is an
// error, because a misspelt key would otherwise silently fall back to its default and the daemon
// would drive the machine with a setting the user did not write.
#include "config/config.hpp"

#include <arpa/inet.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string_view>

#include "gpio/sim_machine.hpp"
#include "config/config_keys.hpp"
#include "config/config_reader.hpp"
#include "config/rt_section.hpp"

namespace stepmod::tools {
namespace {

using std::int64_t;

// Every key's default and range: its row in config/config_keys.hpp (config_key, found at compile
// time), read through ConfigReader; this file states none of them.
constexpr std::string_view kOutputKeys[kOutputLinesPerAxis] = {"step", "dir", "gpo"};
constexpr std::string_view kInputKeys[kInputLinesPerAxis] = {
    "capture", "external", "home", "estop", "cw_limit", "ccw_limit", "enc_a", "enc_b", "enc_z"};

class Parser : ConfigReader {
 public:
  explicit Parser(std::string file) : ConfigReader(std::move(file)) {}

  Config run(std::string_view text) {
    const toml::table root = parse(text);
    Config c;
    c.file = file();
    if (const toml::node* rack = root.get("rack")) {
      fail(rack->source(), "rack",
           "this is a rack file (docs/interface.md section 7), not a module file: stepmodd "
           "--config takes it; a rack's module files are module files of their own");
    }
    check_keys(root, "", "");

    const toml::table* module = sub_table(root, "", "module");
    parse_module(module, c);
    parse_gpio(sub_table(root, "", "gpio"), c);
    parse_rt(sub_table(root, "", "rt"), c);
    // Line offset -> key that uses it, for the uniqueness check across the whole file.
    std::map<int64_t, std::string> used;
    parse_axes(root, module, c, used);
    parse_modbus(sub_table(root, "", "modbus"), c);
    parse_ethernetip(sub_table(root, "", "ethernetip"), c);
    parse_charge_pump(sub_table(root, "", "charge_pump"), c, used);
    return c;
  }

 private:
  // [modbus] (docs/interface.md 6). Every field is set, from its key or the key's default: the
  // server has no defaults of its own.
  void parse_modbus(const toml::table* t, Config& c) const {
    const std::string p = "modbus";
    if (t != nullptr) check_keys(*t, p, "modbus");
    ipc::ModbusOptions& m = c.modbus;
    m.enabled = get_bool(t, p, config_key("modbus", "enabled"));
    m.writes = get_bool(t, p, config_key("modbus", "writes"));
    m.unit_id = static_cast<std::uint8_t>(get_int(t, p, config_key("modbus", "unit_id")));
    m.max_clients = static_cast<unsigned>(get_int(t, p, config_key("modbus", "max_clients")));
    m.idle_timeout_ms =
        static_cast<unsigned>(get_int(t, p, config_key("modbus", "idle_timeout_ms")));
    parse_listen(t, config_key("modbus", "listen"), m.address, m.port);
    if (t != nullptr) parse_allow(t, "modbus", m.allow, EmptyAllow::kRefused);
  }

  // [ethernetip] (docs/ethernetip-design.md), as [modbus]: every field set here.
  void parse_ethernetip(const toml::table* t, Config& c) const {
    const std::string p = "ethernetip";
    if (t != nullptr) check_keys(*t, p, "ethernetip");
    enip::AdapterOptions& e = c.ethernetip;
    e.enabled = get_bool(t, p, config_key("ethernetip", "enabled"));
    const ConfigKey& min = config_key("ethernetip", "rpi_min_us");
    const ConfigKey& max = config_key("ethernetip", "rpi_max_us");
    e.rpi_min_us = static_cast<std::uint32_t>(get_int(t, p, min));
    e.rpi_max_us = static_cast<std::uint32_t>(get_int(t, p, max));
    parse_listen(t, config_key("ethernetip", "listen"), e.address, e.port);
    // `allow = []` is the contract's own example for "any originator" (docs/interface.md 9).
    if (t != nullptr) parse_allow(t, "ethernetip", e.allow, EmptyAllow::kMeansAny);
    if (e.rpi_max_us < e.rpi_min_us) {
      const toml::node* n = t != nullptr ? t->get(max.key) : nullptr;
      fail(n != nullptr ? n->source() : toml::source_region{}, "ethernetip.rpi_max_us",
           "is " + std::to_string(e.rpi_max_us) + ", below ethernetip.rpi_min_us (" +
               std::to_string(e.rpi_min_us) + "): raise it or lower rpi_min_us");
    }
  }

  // `listen` of a server's table: a numeric IPv4 address and a port (the default is parsed like
  // a written value).
  void parse_listen(const toml::table* t, const ConfigKey& k, std::string& address,
                    std::uint16_t& port_out) const {
    const toml::node* n = t != nullptr ? t->get(k.key) : nullptr;
    const auto* s = n != nullptr ? n->as_string() : nullptr;
    const std::string text = n == nullptr ? std::string(k.text) : s != nullptr ? s->get() : "";
    const auto colon = text.rfind(':');
    in_addr addr{};
    bool ok = colon != std::string::npos && colon > 0 &&
              ::inet_pton(AF_INET, text.substr(0, colon).c_str(), &addr) == 1;
    long port = 0;
    if (ok) {
      const std::string ps = text.substr(colon + 1);
      ok = !ps.empty() && ps.size() <= 5 && ps.find_first_not_of("0123456789") == std::string::npos;
      if (ok) port = std::stol(ps);
      ok = ok && port >= 1 && port <= 65535;  // TCP's ports
    }
    if (!ok) {
      fail(n != nullptr ? n->source() : toml::source_region{},
           std::string(k.table) + "." + std::string(k.key),
           "must be \"IPv4-ADDRESS:PORT\" with a port 1..65535, e.g. \"" + std::string(k.text) +
               "\"");
    }
    address = text.substr(0, colon);
    port_out = static_cast<std::uint16_t>(port);
  }

  // An empty list: refused where the key's only documented form is a non-empty list ([modbus]),
  // any source where the contract writes `allow = []` for "any" ([ethernetip]).
  enum class EmptyAllow { kRefused, kMeansAny };

  // allow = ["127.0.0.1", "10.0.0.0/8", ...] of a server's table: where peers may come from.
  void parse_allow(const toml::table* t, const std::string& table,
                   std::vector<ipc::AllowNet>& allow, EmptyAllow empty) const {
    const toml::node* n = t->get("allow");
    if (n == nullptr) return;
    const auto* list = n->as_array();
    if (list != nullptr && list->empty() && empty == EmptyAllow::kMeansAny) return;
    if (list == nullptr || list->empty()) {
      fail(n->source(), table + ".allow",
           "must be a non-empty list of IPv4 addresses or networks, e.g. [\"127.0.0.1\", "
           "\"10.0.0.0/8\"]");
    }
    for (const toml::node& e : *list) {
      const auto* s = e.as_string();
      const auto net = s != nullptr ? ipc::parse_allow_net(s->get()) : std::nullopt;
      if (!net) {
        fail(e.source(), table + ".allow",
             "each entry must be an IPv4 address or ADDRESS/PREFIX (0..32) in quotes, e.g. "
             "\"10.0.0.0/8\"");
      }
      allow.push_back(*net);
    }
  }

  void parse_module(const toml::table* m, Config& c) const {
    const std::string p = "module";
    const ConfigKey& kType = config_key("module", "type");
    if (m != nullptr) check_keys(*m, p, "module");
    const toml::node* type = m != nullptr ? m->get("type") : nullptr;
    if (type == nullptr) {
      toml::source_region where{};
      if (m != nullptr) where = m->source();
      fail(where, "module.type", "required: " + choices_text(kType, " or "));
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
      fail(type->source(), "module.type", "must be " + choices_text(kType, " or "));
    }
    c.name = parse_name(m);
    c.scan_ns = get_ns(m, p, config_key("module", "scan_us"));
    c.plc_timeout_ns = get_ns(m, p, config_key("module", "plc_timeout_ms"));
  }

  // [module] name: it names /dev/shm/stepmod.NAME, so a short run of a few safe characters.
  std::string parse_name(const toml::table* m) const {
    const ConfigKey& k = config_key("module", "name");
    const toml::node* n = m != nullptr ? m->get(k.key) : nullptr;
    if (n == nullptr) return std::string(k.text);
    const auto* s = n->as_string();
    const auto size = s != nullptr ? static_cast<std::int64_t>(s->get().size()) : 0;
    bool ok = s != nullptr && size >= k.min && size <= k.max;
    if (ok) {
      for (char ch : s->get()) {
        ok = ok && ((ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '-' || ch == '_');
      }
    }
    if (!ok) {
      fail(n->source(), "module.name",
           "must be " + std::to_string(k.min) + ".." + std::to_string(k.max) +
               " characters of a-z, 0-9, '-' and '_' (it names /dev/shm/stepmod.NAME)");
    }
    return s->get();
  }

  void parse_gpio(const toml::table* g, Config& c) const {
    const std::string p = "gpio";
    if (g != nullptr) check_keys(*g, p, "gpio");
    c.backend = get_choice(g, p, config_key("gpio", "backend")) == "gpiod" ? Config::Backend::kGpiod
                                                                           : Config::Backend::kSim;
    const ConfigKey& chip = config_key("gpio", "chip");
    c.chip = chip.text;
    if (const toml::node* n = g != nullptr ? g->get(chip.key) : nullptr) {
      const auto* s = n->as_string();
      if (s == nullptr || static_cast<std::int64_t>(s->get().size()) < chip.min) {
        fail(n->source(), "gpio.chip",
             "must be a chip name (" + std::string(chip.text) + "), a /dev path or a label");
      }
      c.chip = s->get();
    }
  }

  void parse_rt(const toml::table* r, Config& c) const {
    read_rt_section(*this, r, c);
    if (r != nullptr) c.rt_table_line = std::max(1u, r->source().begin.line);
  }

  void parse_axes(const toml::table& root, const toml::table* module, Config& c,
                  std::map<int64_t, std::string>& used) const {
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
    for (std::size_t i = 0; i < count; ++i) {
      c.axes.push_back(
          parse_axis(*(*arr)[i].as_table(), i, c.type, c.backend == Config::Backend::kGpiod, used));
    }
  }

  AxisSection parse_axis(const toml::table& t, std::size_t index, ModuleType type, bool gpiod,
                         std::map<int64_t, std::string>& used) const {
    // 1-based like the contract's "axis 1, then axis 2" and the VCD names axis1.step.
    const std::string p = "axis[" + std::to_string(index + 1) + "]";
    check_keys(t, p, "axis");
    AxisSection a;
    auto line = [&](std::string_view key, bool input, gpio::LineOptions& opt) {
      return unique_line(t, p, key, {input, gpiod, "axis"}, opt, used);
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
    a.step_pulse_ns = get_ns(&t, p, config_key("axis", "step_pulse_ns"));
    a.dir_setup_ns = get_ns(&t, p, config_key("axis", "dir_setup_ns"));
    // Output steps of lag above Vs (docs/slip.md).
    a.lag_limit_steps =
        static_cast<std::uint32_t>(get_int(&t, p, config_key("axis", "lag_limit_steps")));
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

  // What a line key is: its direction, whether the chip is real (gpiod), and the table of its
  // row in config/config_keys.hpp.
  struct LineKind {
    bool input = false;
    bool gpiod = false;
    std::string_view table;
  };

  // A line key (line_entry) whose offset no other line key of the file has (`used`: offset ->
  // key, filled as the keys are read).
  std::optional<unsigned> unique_line(const toml::table& t, const std::string& p,
                                      std::string_view key, const LineKind& kind,
                                      gpio::LineOptions& opt,
                                      std::map<int64_t, std::string>& used) const {
    const auto v = line_entry(t, p, key, kind, opt);
    if (!v) return std::nullopt;
    const auto [it, fresh] = used.emplace(*v, join(p, key));
    if (!fresh) {
      fail(t.get(key)->source(), join(p, key),
           "line offset " + std::to_string(*v) + " is already used by '" + it->second + "'");
    }
    return static_cast<unsigned>(*v);
  }

  // A line key: its offset (`home = 5`), or the offset with electrical options
  // (`home = { offset = 5, bias = "pull-up", active_low = true, debounce_us = 2000 }`). The
  // options a plain offset leaves out, and those a table leaves out, get their defaults.
  std::optional<int64_t> line_entry(const toml::table& t, const std::string& p,
                                    std::string_view key, const LineKind& kind,
                                    gpio::LineOptions& opt) const {
    const bool input = kind.input;
    const toml::node* n = t.get(key);
    if (n == nullptr) return std::nullopt;
    const toml::table* o = n->as_table();
    const std::string q = join(p, key);
    std::optional<int64_t> off;
    if (o == nullptr) {
      off = opt_int(&t, p, *find_config_key(kind.table, key));
    } else {
      if (input) {
        check_keys(*o, q, {"offset", "active_low", "bias", "debounce_us"});
      } else {
        check_keys(*o, q, {"offset", "active_low", "drive"});
      }
      off = opt_int(o, q, config_key("line", "offset"));
      if (!off) fail(o->source(), join(q, "offset"), "required: the line offset on the chip");
    }
    opt.active_low = get_bool(o, q, config_key("line", "active_low"));
    if (input) {
      line_input_options(o, q, kind.gpiod, opt);
    } else {
      const std::string d = get_choice(o, q, config_key("line", "drive"));
      opt.drive = d == "open-drain"    ? gpio::Drive::kOpenDrain
                  : d == "open-source" ? gpio::Drive::kOpenSource
                                       : gpio::Drive::kPushPull;
    }
    return off;
  }

  // An input line's options (`o` null: all defaults).
  void line_input_options(const toml::table* o, const std::string& q, bool gpiod,
                          gpio::LineOptions& opt) const {
    const std::string b = get_choice(o, q, config_key("line", "bias"));
    opt.bias = b == "pull-up"     ? gpio::Bias::kPullUp
               : b == "pull-down" ? gpio::Bias::kPullDown
               : b == "disabled"  ? gpio::Bias::kDisabled
                                  : gpio::Bias::kAsIs;
    opt.debounce_us = static_cast<std::uint32_t>(get_int(o, q, config_key("line", "debounce_us")));
    if (opt.debounce_us != 0 && gpiod && !gpio::gpiod_capabilities().debounce) {
      fail(o->get("debounce_us")->source(), join(q, "debounce_us"),
           "kernel debounce needs libgpiod 2; this stepmod is built with libgpiod " +
               std::to_string(gpio::gpiod_capabilities().libgpiod_major) +
               ".x (v1 uAPI, no debounce): debounce in hardware (RC filter) or remove the key");
    }
  }

  // [charge_pump] (an extension, docs/safety.md "Charge pump"): off unless `line` names a line;
  // the control thread toggles it every half_period_scans scans, so the frequency must give a
  // whole number of scans per half period.
  void parse_charge_pump(const toml::table* t, Config& c,
                         std::map<int64_t, std::string>& used) const {
    if (t == nullptr) return;
    const std::string p = "charge_pump";
    check_keys(*t, p, "charge_pump");
    ChargePumpSection& cp = c.charge_pump;
    cp.line = unique_line(*t, p, "line", {false, c.backend == Config::Backend::kGpiod, p},
                          cp.line_opt, used);
    const ConfigKey& k = config_key("charge_pump", "frequency_hz");
    const toml::node* n = t->get(k.key);
    if (!cp.line) {
      if (n != nullptr) fail(n->source(), join(p, k.key), "needs a line (key 'charge_pump.line')");
      return;
    }
    cp.frequency_hz = static_cast<unsigned>(get_int(t, p, k));
    const int64_t scan_us = c.scan_ns / kNsPerUs;
    constexpr int64_t kHalfSecondUs = 500'000;  // half a period of 1 Hz
    if (kHalfSecondUs % cp.frequency_hz != 0 || (kHalfSecondUs / cp.frequency_hz) % scan_us != 0) {
      fail(n != nullptr ? n->source() : t->source(), join(p, k.key),
           std::string(n != nullptr ? "" : "the default ") + std::to_string(cp.frequency_hz) +
               " Hz is not a whole number of scans per half period at module.scan_us = " +
               std::to_string(scan_us) + ": use " + whole_scan_frequencies(k, scan_us) +
               ", or change module.scan_us");
    }
    cp.half_period_scans = static_cast<unsigned>(kHalfSecondUs / cp.frequency_hz / scan_us);
  }

  // The frequencies within `k`'s range whose half period is a whole number of `scan_us` scans,
  // highest first: "500, 250, 125 or 100 Hz".
  static std::string whole_scan_frequencies(const ConfigKey& k, int64_t scan_us) {
    std::vector<int64_t> hz;
    for (int64_t half = scan_us; half <= 500'000 / k.min; half += scan_us) {
      if (500'000 % half == 0 && 500'000 / half <= k.max) hz.push_back(500'000 / half);
    }
    if (hz.empty()) return "no frequency in " + std::to_string(k.min) + ".." + std::to_string(k.max);
    std::string text;
    for (std::size_t i = 0; i < hz.size(); ++i) {
      text += (i == 0 ? "" : i + 1 == hz.size() ? " or " : ", ") + std::to_string(hz[i]);
    }
    return text + " Hz";
  }

  // The drive-enable output's keys (an extension: off unless `enable` names a line).
  void parse_enable(const toml::table& t, const std::string& p, AxisSection& a) const {
    if (!a.enable) {
      for (std::string_view k : {"enable_delay_us", "enable_release_on"}) {
        if (const toml::node* n = t.get(k)) {
          fail(n->source(), join(p, k), "needs an enable line (key 'enable')");
        }
      }
      return;
    }
    a.enable_delay_ns = get_ns(&t, p, config_key("axis", "enable_delay_us"));
    // In the order of the key's choices.
    constexpr std::uint8_t kBits[] = {kReleaseOnEStop, kReleaseOnFault, kReleaseOnPlcLoss,
                                      kReleaseOnConfigMode};
    for (unsigned i : get_choice_list(&t, p, config_key("axis", "enable_release_on"))) {
      a.enable_release |= kBits[i];
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

  // Every field is set, from its key or the key's default (`s` null: all defaults).
  SimAxisConfig parse_sim(const toml::table* s, const std::string& p) const {
    SimAxisConfig c;
    if (s != nullptr) check_keys(*s, p, "axis.sim");
    c.start_position = get_int(s, p, config_key("axis.sim", "start_position"));
    c.cw_limit_at = opt_int(s, p, config_key("axis.sim", "cw_limit_at"));
    c.ccw_limit_at = opt_int(s, p, config_key("axis.sim", "ccw_limit_at"));
    if (c.cw_limit_at && c.ccw_limit_at && !(*c.ccw_limit_at < *c.cw_limit_at)) {
      fail(s->get("ccw_limit_at")->source(), join(p, "ccw_limit_at"),
           "must be less than cw_limit_at (" + std::to_string(*c.cw_limit_at) + ")");
    }
    c.home_from = opt_int(s, p, config_key("axis.sim", "home_from"));
    c.home_to = opt_int(s, p, config_key("axis.sim", "home_to"));
    if (c.home_from.has_value() != c.home_to.has_value()) {
      const std::string_view present = c.home_from ? "home_from" : "home_to";
      fail(s->get(present)->source(), join(p, present),
           "home_from and home_to must be given together");
    }
    if (c.home_from && *c.home_from > *c.home_to) {
      fail(s->get("home_to")->source(), join(p, "home_to"),
           "must be >= home_from (" + std::to_string(*c.home_from) + ")");
    }
    c.contacts_nc = get_choice(s, p, config_key("axis.sim", "contacts")) == "NC";
    c.encoder_ratio = get_number(s, p, config_key("axis.sim", "encoder_ratio"));
    c.marker_every = opt_int(s, p, config_key("axis.sim", "marker_every"));
    c.event_ring = sim_event_ring(s, p);
    return c;
  }

  // [axis.sim] event_ring: the simulated input event FIFO, a power of two (SpscRing).
  std::size_t sim_event_ring(const toml::table* s, const std::string& p) const {
    const ConfigKey& k = config_key("axis.sim", "event_ring");
    const int64_t v = get_int(s, p, k);
    if ((v & (v - 1)) != 0) {
      fail(s->get(k.key)->source(), join(p, k.key),
           "must be a power of two, " + std::to_string(k.min) + " .. " + std::to_string(k.max) +
               " (default " + std::to_string(k.def) + ")");
    }
    return static_cast<std::size_t>(v);
  }
};

}  // namespace

Config parse_config(std::string_view toml_text, const std::string& file_name) {
  return Parser(file_name).run(toml_text);
}

std::string read_config_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(path + ": cannot read: " + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Config load_config(const std::string& path) {
  return parse_config(read_config_file(path), path);
}

}  // namespace stepmod::tools

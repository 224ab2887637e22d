// The rules between a rack's modules (docs/interface.md section 7). Each module file is valid on
// its own already; what is checked here only a rack can break.
#include <map>
#include <string>

#include "config/rack_config.hpp"

namespace stepmod::tools {
namespace {

[[noreturn]] void refuse(const RackConfig& rack, const std::string& what) {
  throw ConfigError(rack.file + ": " + what);
}

void check_names(const RackConfig& rack) {
  std::map<std::string, const Config*> seen;
  for (const Config& m : rack.modules) {
    const auto [it, fresh] = seen.emplace(m.name, &m);
    if (fresh) continue;
    refuse(rack, "key 'module.name': the name '" + m.name + "' is used by both " +
                     it->second->file + " and " + m.file +
                     ": each module needs its own (it names its image /dev/shm/stepmod.NAME)");
  }
}

// A gpiod chip as the user may write it: "gpiochip0" or "/dev/gpiochip0".
std::string chip_id(const std::string& chip) {
  constexpr std::string_view kDev = "/dev/";
  return chip.starts_with(kDev) ? chip.substr(kDev.size()) : chip;
}

// Every wired line of a module: "axis[N].KEY" -> offset.
std::map<std::string, unsigned> lines_of(const Config& m) {
  std::map<std::string, unsigned> lines;
  for (std::size_t a = 0; a < m.axes.size(); ++a) {
    const std::string p = "axis[" + std::to_string(a + 1) + "].";
    const AxisSection& s = m.axes[a];
    for (unsigned l = 0; l < kOutputLinesPerAxis; ++l) {
      if (s.out[l]) lines[p + std::string(gpio::output_key(static_cast<OutputLine>(l)))] = *s.out[l];
    }
    for (unsigned l = 0; l < kInputLinesPerAxis; ++l) {
      if (s.in[l]) lines[p + std::string(gpio::input_key(static_cast<InputLine>(l)))] = *s.in[l];
    }
    if (s.enable) lines[p + "enable"] = *s.enable;
  }
  if (m.charge_pump.line) lines["charge_pump.line"] = *m.charge_pump.line;
  return lines;
}

// On real chips a line is one module's (the simulated machines are each module's own).
void check_lines(const RackConfig& rack) {
  struct Owner {
    const Config* module;
    std::string key;
  };
  std::map<std::pair<std::string, unsigned>, Owner> owners;
  for (const Config& m : rack.modules) {
    if (m.backend != Config::Backend::kGpiod) continue;
    for (const auto& [key, offset] : lines_of(m)) {
      const auto [it, fresh] = owners.emplace(std::pair{chip_id(m.chip), offset}, Owner{&m, key});
      if (fresh || it->second.module == &m) continue;
      refuse(rack, "key '" + key + "' of module '" + m.name + "' (" + m.file + "): line " +
                       std::to_string(offset) + " of chip '" + m.chip +
                       "' is already used by key '" + it->second.key + "' of module '" +
                       it->second.module->name + "' (" + it->second.module->file +
                       "): a line belongs to one module only");
    }
  }
}

bool same_server_keys(const ipc::ModbusOptions& a, const ipc::ModbusOptions& b) {
  bool same = a.max_clients == b.max_clients && a.idle_timeout_ms == b.idle_timeout_ms &&
              a.allow.size() == b.allow.size();
  for (std::size_t i = 0; same && i < a.allow.size(); ++i) {
    same = a.allow[i].network == b.allow[i].network && a.allow[i].mask == b.allow[i].mask;
  }
  return same;
}

// Modules with one listen address share one server: their unit ids tell them apart, and the
// server's own keys must agree.
void check_modbus(const RackConfig& rack) {
  std::map<std::string, const Config*> first;  // "address:port" -> its first module
  std::map<std::pair<std::string, unsigned>, const Config*> units;
  for (const Config& m : rack.modules) {
    if (!m.modbus.enabled) continue;
    const std::string listen = m.modbus.address + ":" + std::to_string(m.modbus.port);
    const Config* f = first.emplace(listen, &m).first->second;
    const auto [u, fresh] = units.emplace(std::pair{listen, m.modbus.unit_id}, &m);
    if (!fresh) {
      refuse(rack, "key 'modbus.unit_id': modules '" + u->second->name + "' (" + u->second->file +
                       ") and '" + m.name + "' (" + m.file + ") share the Modbus address " +
                       listen + " with the same unit id " + std::to_string(m.modbus.unit_id) +
                       ": give each its own");
    }
    if (!same_server_keys(f->modbus, m.modbus)) {
      refuse(rack, "keys 'modbus.max_clients', 'modbus.idle_timeout_ms', 'modbus.allow': modules '" +
                       f->name + "' (" + f->file + ") and '" + m.name + "' (" + m.file +
                       ") share the Modbus server on " + listen +
                       " and must give it the same values");
    }
  }
}

// Each module's adapter has an address of its own: its I/O is on UDP 2222 of that address, so
// even two ports of one address would clash (docs/ethernetip-design.md).
void check_ethernetip(const RackConfig& rack) {
  std::map<std::string, const Config*> owner;  // address -> the module that has it
  for (const Config& m : rack.modules) {
    if (!m.ethernetip.enabled) continue;
    const auto [it, fresh] = owner.emplace(m.ethernetip.address, &m);
    if (fresh) continue;
    refuse(rack, "key 'ethernetip.listen': modules '" + it->second->name + "' (" +
                     it->second->file + ") and '" + m.name + "' (" + m.file +
                     ") both listen on address " + m.ethernetip.address +
                     " (class 1 I/O is on UDP 2222 of it): give each module its own address "
                     "(a board can carry several)");
  }
}

}  // namespace

void check_rack(const RackConfig& rack) {
  check_names(rack);
  check_lines(rack);
  check_modbus(rack);
  check_ethernetip(rack);
}

}  // namespace stepmod::tools

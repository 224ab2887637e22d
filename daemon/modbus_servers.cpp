#include "daemon/modbus_servers.hpp"

#include <spdlog/spdlog.h>

#include <map>
#include <stdexcept>
#include <string>

namespace stepmod::tools {

std::vector<std::unique_ptr<ipc::ModbusServer>> start_modbus_servers(
    std::span<const Config> modules) {
  // By listen address, in the order the addresses first appear.
  std::vector<std::vector<ipc::ModbusUnit>> groups;
  std::map<std::string, std::size_t> group_of;
  for (const Config& m : modules) {
    if (!m.modbus.enabled) continue;
    const std::string listen = m.modbus.address + ":" + std::to_string(m.modbus.port);
    const auto [it, fresh] = group_of.emplace(listen, groups.size());
    if (fresh) groups.emplace_back();
    groups[it->second].push_back({m.name, m.modbus});
  }
  std::vector<std::unique_ptr<ipc::ModbusServer>> servers;
  for (const std::vector<ipc::ModbusUnit>& units : groups) {
    std::string names;
    for (const ipc::ModbusUnit& u : units) {
      names += (names.empty() ? "'" : ", '") + u.name + "' (unit " +
               std::to_string(u.options.unit_id) + ", writes " +
               (u.options.writes ? "accepted" : "refused") + ")";
    }
    try {
      servers.push_back(std::make_unique<ipc::ModbusServer>(units));
    } catch (const std::exception& e) {
      throw std::runtime_error("module " + names + ": " + e.what());
    }
    spdlog::info("modbus: serving on {}: {}", servers.back()->endpoint(), names);
  }
  return servers;
}

}  // namespace stepmod::tools

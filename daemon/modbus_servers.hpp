#pragma once
// The rack's Modbus/TCP servers (docs/interface.md sections 6 and 7): one per listen address,
// serving every module with [modbus] enabled on it, told apart by unit id. Built once every
// module's image exists; each server runs its own thread.
#include <memory>
#include <span>
#include <vector>

#include "config/config.hpp"
#include "ipc/modbus_server.hpp"

namespace stepmod::tools {

// Throws std::runtime_error naming the modules of an address that cannot be bound.
std::vector<std::unique_ptr<ipc::ModbusServer>> start_modbus_servers(
    std::span<const Config> modules);

}  // namespace stepmod::tools

#pragma once
// The rack's EtherNet/IP adapters (docs/ethernetip-design.md): one per module with [ethernetip]
// enabled, each on its own address (config/rack_rules.cpp), each with its own thread. Built once
// every module's image exists; each adapter raises its module's "PLC not in Run" flag, which the
// module's control loop reads each scan (the deadman).
#include <memory>
#include <span>
#include <vector>

#include "daemon/module_runtime.hpp"
#include "fieldbus/enip/adapter.hpp"

namespace stepmod::tools {

// Throws std::runtime_error naming the module whose adapter cannot start.
std::vector<std::unique_ptr<enip::Adapter>> start_enip_adapters(
    std::span<const std::unique_ptr<ModuleRuntime>> modules);

}  // namespace stepmod::tools

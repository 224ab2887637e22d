#include "daemon/enip_adapters.hpp"

#include <spdlog/spdlog.h>

#include <fstream>
#include <stdexcept>
#include <string>

#include "fieldbus/enip/identity.hpp"

namespace stepmod::tools {

namespace {
// The Identity object's serial number is stable across restarts and distinct per board: it is
// derived from the machine id (empty where there is none: then from the module name alone).
std::string machine_id() {
  std::string id;
  std::ifstream("/etc/machine-id") >> id;
  return id;
}
}  // namespace

std::vector<std::unique_ptr<enip::Adapter>> start_enip_adapters(
    std::span<const std::unique_ptr<ModuleRuntime>> modules) {
  std::vector<std::unique_ptr<enip::Adapter>> adapters;
  const std::string machine = machine_id();
  for (const std::unique_ptr<ModuleRuntime>& m : modules) {
    const Config& c = m->config();
    if (!c.ethernetip.enabled) continue;
    enip::Adapter::Setup s;
    s.module_name = c.name;
    s.options = c.ethernetip;
    s.serial = enip::identity_serial(machine, c.name);
    s.plc_not_in_run = &m->plc_not_in_run();
    try {
      adapters.push_back(std::make_unique<enip::Adapter>(s));
    } catch (const std::exception& e) {
      throw std::runtime_error("module '" + c.name + "' (" + c.file + "): " + e.what());
    }
    spdlog::info(
        "ethernetip: module '{}' adapter on {} (TCP and UDP), class 1 I/O on UDP {}; RPI {} … "
        "{} us; serial {:#010x}",
        c.name, adapters.back()->endpoint(), enip::kIoPort, c.ethernetip.rpi_min_us,
        c.ethernetip.rpi_max_us, s.serial);
  }
  return adapters;
}

}  // namespace stepmod::tools

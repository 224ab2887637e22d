#pragma once
// [modbus] of the configuration file (INTERFACE.md section 6), as the server uses it.
#include <cstdint>
#include <string>
#include <vector>

#include "ipc/modbus_allow.hpp"

namespace stepmod::ipc {

struct ModbusOptions {
  bool enabled = false;
  std::string address = "127.0.0.1";  // numeric IPv4 address to bind to
  std::uint16_t port = 1502;
  std::uint8_t unit_id = 1;
  bool writes = false;  // true: a master may write the output words (it then is the PLC)
  unsigned max_clients = 4;
  // Source addresses/networks a connection may come from; empty: any (the listen address is
  // then the only gate).
  std::vector<AllowNet> allow;
};

}  // namespace stepmod::ipc

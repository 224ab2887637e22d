#pragma once
// [modbus] of the configuration file (docs/interface.md section 6), as the server uses it.
#include <cstdint>
#include <string>
#include <vector>

#include "ipc/modbus_allow.hpp"

namespace stepmod::ipc {

// No defaults here: config/config.cpp sets every field, a key the file leaves out to its default
// in the configuration's key table (config/config_keys.hpp), so that no default is stated twice.
struct ModbusOptions {
  bool enabled = false;
  std::string address;  // numeric IPv4 address to bind to
  std::uint16_t port = 0;
  std::uint8_t unit_id = 0;
  bool writes = false;  // true: a master may write the output words (it then is the PLC)
  // Connections served at once; a new one beyond them closes the longest-idle one
  // (ipc/modbus_connection.hpp).
  unsigned max_clients = 0;
  // A connection nothing has come from for this long is closed: an idle socket does not hold one
  // of the max_clients places for ever.
  unsigned idle_timeout_ms = 0;
  // Source addresses/networks a connection may come from; empty: any (the listen address is
  // then the only gate).
  std::vector<AllowNet> allow;
};

}  // namespace stepmod::ipc

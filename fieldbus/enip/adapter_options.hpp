#pragma once
// [ethernetip] of the configuration file (docs/ethernetip-design.md, "Where it sits in
// stepmod"), as the adapter uses it. No defaults here: config/config.cpp sets every field from
// its key or the key's default in config/config_keys.hpp, so that no default is stated twice.
#include <cstdint>
#include <string>
#include <vector>

#include "ipc/modbus_allow.hpp"

namespace stepmod::enip {

// Class 1 I/O is on this UDP port of the listen address (the port every scanner sends to).
inline constexpr std::uint16_t kIoPort = 2222;

struct AdapterOptions {
  bool enabled = false;
  std::string address;     // numeric IPv4 address: TCP and UDP encapsulation, UDP I/O
  std::uint16_t port = 0;  // encapsulation, TCP and UDP (44818)
  // Originator addresses/networks: a TCP connection, a UDP request or an I/O packet from
  // elsewhere is dropped. Empty: any.
  std::vector<ipc::AllowNet> allow;
  std::uint32_t rpi_min_us = 0;
  std::uint32_t rpi_max_us = 0;
};

}  // namespace stepmod::enip

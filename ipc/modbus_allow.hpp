#pragma once
// [modbus] allow: the source addresses and networks a Modbus/TCP connection may come from.
// Modbus has no authentication; this list (with a listen address only the PLC's host reaches)
// is the only gate in front of a server that accepts writes.
#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace stepmod::ipc {

struct AllowNet {
  std::uint32_t network = 0;  // host byte order, already masked
  std::uint32_t mask = 0;     // host byte order
};

// "10.0.0.0/8", "192.168.1.20" (= /32); nullopt if not a numeric IPv4 address with an optional
// prefix length 0..32.
std::optional<AllowNet> parse_allow_net(const std::string& text);

// Whether `address` (IPv4, network byte order) is in one of `nets`; an empty list allows all.
bool address_allowed(std::span<const AllowNet> nets, std::uint32_t address_be) noexcept;

}  // namespace stepmod::ipc

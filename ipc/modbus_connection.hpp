#pragma once
// One Modbus/TCP connection as the server keeps it, and the rules that end it: its time-outs and
// which connection gives up its place when [modbus] max_clients are connected and another comes
// (docs/hardening.md). No sockets here (ipc/modbus_server does the TCP side), so the rules are
// unit-tested on plain values.
#include <cstdint>
#include <list>
#include <string>
#include <vector>

#include "core/clock.hpp"

namespace stepmod::ipc {

// A frame must be complete this long after its first byte arrived, else the connection is closed
// (a request is one TCP segment from any real master).
inline constexpr Nanos kModbusFrameTimeout = 500 * kNsPerMs;
// After a malformed frame the answers to the frames before it are still sent; a client that does
// not take them within this long is closed all the same.
inline constexpr Nanos kModbusCloseTimeout = 500 * kNsPerMs;

struct ModbusConnection {
  int fd = -1;
  std::string peer;
  std::vector<std::uint8_t> in;
  std::vector<std::uint8_t> out;
  Nanos frame_start = 0;    // when the first byte of the incomplete frame in `in` came; 0: none
  Nanos last_heard = 0;     // when it was accepted, then when its last byte came
  bool served = false;      // it has sent at least one whole frame
  Nanos closing_since = 0;  // a malformed frame came: answers owed are sent, then it is closed
};

// When `c` is next to be closed for a time-out, and why (for the log).
struct ModbusTimeout {
  Nanos at = 0;
  const char* why = "";
  bool idle = false;  // the idle time-out (logged apart: the others are the client's fault)
};
ModbusTimeout next_timeout(const ModbusConnection& c, Nanos idle_timeout) noexcept;

// The connection to close so that a new one can be served, when max_clients are connected
// (`clients` not empty). First one already closing after a malformed frame; then one that has
// never sent a whole frame (it holds a place and asks nothing: the idle sockets that kept a
// PLC out for good before); only then one that has been served. Within each kind, the one heard
// from longest ago. So a PLC polling every 10-100 ms is never chosen while a connection that has
// asked nothing is there, however recently that one connected.
std::list<ModbusConnection>::iterator eviction_choice(std::list<ModbusConnection>& clients);

}  // namespace stepmod::ipc

#pragma once
// Modbus/TCP server of docs/interface.md section 6, serving one module's shared-memory image, or
// in a rack (section 7) those of every module with the same listen address, told apart by the
// request's unit id (another unit id: exception 0B). It
// runs in its own thread at normal priority and reaches the image only through its seqlocks
// (ModbusMap), never through the control thread: a flood of requests costs this thread CPU time,
// not a scan.
//
// No client can hold up another (docs/hardening.md): every socket is non-blocking, each
// connection has its own receive and send buffers, and one poll() serves them all, so a client
// that sends a frame a byte at a time delays nobody; a frame not complete kFrameTimeout after its
// first byte closes its connection, and so does [modbus] idle_timeout_ms without a byte. Nor can
// clients that connect and ask nothing keep the PLC out: with max_clients connected, a new
// connection closes the longest-idle one (ipc/modbus_connection.hpp says which). Frames are
// checked as Modbus/TCP defines them (ipc/mbap.hpp): a malformed one gets exception 03 or a
// closed connection, never a normal answer; the frames before it are answered first.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "core/clock.hpp"
#include "ipc/modbus_connection.hpp"
#include "ipc/modbus_options.hpp"

namespace stepmod::ipc {

// One module a server serves: its image's name and its [modbus] table (its unit id and writes).
struct ModbusUnit {
  std::string name;
  ModbusOptions options;
};

class ModbusServer {
 public:
  static constexpr Nanos kFrameTimeout = kModbusFrameTimeout;
  // Refused connections (allow), connections closed for a new one and idle connections closed
  // are each logged at most once per this period, with the number since the last such line.
  static constexpr Nanos kLogPeriod = 10 * kNsPerSec;

  // Maps the image of module `name` (created by this process's ShmImage beforehand), binds
  // options.address:port and starts serving. Throws IpcError (address in use, bad address...).
  ModbusServer(const std::string& name, const ModbusOptions& options)
      : ModbusServer(std::vector<ModbusUnit>{{name, options}}) {}
  // Several modules on one address: the server's keys (address, port, max_clients, allow,
  // idle_timeout_ms) are the first unit's (config/rack_config.hpp checks that they agree); the
  // unit ids must differ.
  explicit ModbusServer(std::span<const ModbusUnit> units);
  ~ModbusServer();  // stop(); closes every connection
  ModbusServer(const ModbusServer&) = delete;
  ModbusServer& operator=(const ModbusServer&) = delete;

  // Wakes the thread, which closes the sockets and ends; idempotent.
  void stop() noexcept;

  std::string endpoint() const;  // "127.0.0.1:1502"

 private:
  struct Impl;
  void run() noexcept;

  std::unique_ptr<Impl> impl_;
  ModbusOptions options_;  // the server's keys (the first unit's)
  std::thread thread_;
};

}  // namespace stepmod::ipc

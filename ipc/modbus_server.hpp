#pragma once
// Modbus/TCP server of INTERFACE.md section 6 (libmodbus for the framing), serving one module's
// shared-memory image. It runs in its own thread at normal priority and reaches the image only
// through its seqlocks (ModbusMap), never through the control thread: a flood of requests costs
// this thread CPU time, not a scan.
#include <cstdint>
#include <memory>
#include <string>
#include <thread>

#include "ipc/modbus_options.hpp"

namespace stepmod::ipc {

class ModbusServer {
 public:
  // Maps the image of module `name` (created by this process's ShmImage beforehand), binds
  // options.address:port and starts serving. Throws IpcError (address in use, bad address...).
  ModbusServer(const std::string& name, const ModbusOptions& options);
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
  ModbusOptions options_;
  std::thread thread_;
};

}  // namespace stepmod::ipc

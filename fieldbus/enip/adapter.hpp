#pragma once
// The EtherNet/IP adapter of one module (docs/ethernetip-design.md): encapsulation on TCP and
// UDP (the listen address, 44818), class 1 I/O on UDP 2222 of the same address, served by one
// thread of its own at normal priority (SCHED_OTHER) with one poll() over its sockets and a
// timerfd at the connection table's next due time (a T→O packet or a timeout). It reaches the
// module only through the shared-memory image (ImageAssemblies: seqlock writes, as a PLC does),
// and tells the control thread through `plc_not_in_run` when the owner PLC has left Run (Idle,
// timeout, Forward_Close): the deadman of docs/ethernetip-design.md, which ipc::PlcSupervisor
// treats as a stale heartbeat. Buffers are fixed: steady-state I/O allocates nothing.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>

#include "fieldbus/enip/adapter_options.hpp"

namespace stepmod::enip {

// What the adapter counts (read from any thread; for tests, benches and the log).
struct AdapterCounters {
  std::atomic<std::uint64_t> run_writes{0};  // O→T Run packets written to the image
  std::atomic<std::uint64_t> io_dropped{0};  // O→T packets dropped (unknown, old, bad)
  std::atomic<std::uint64_t> to_sent{0};     // T→O packets sent
  std::atomic<std::uint64_t> refused{0};     // connections and datagrams not allowed
};

class Adapter {
 public:
  struct Setup {
    std::string module_name;  // its image, /dev/shm/stepmod.NAME, created beforehand
    AdapterOptions options;
    std::uint32_t serial = 0;  // Identity attribute 6 (identity_serial)
    // The deadman: true while the owner PLC is out of Run (null: nobody reads it).
    std::atomic<bool>* plc_not_in_run = nullptr;
  };

  // Maps the image, binds the sockets and starts the thread. Throws ipc::IpcError (address in
  // use, not a stepmod image...).
  explicit Adapter(const Setup& setup);
  ~Adapter();  // stop()
  Adapter(const Adapter&) = delete;
  Adapter& operator=(const Adapter&) = delete;

  // Wakes the thread, which closes every socket and ends; idempotent.
  void stop() noexcept;

  std::string endpoint() const;  // "127.0.0.1:44818"
  const AdapterCounters& counters() const noexcept;

 private:
  struct Impl;
  void run() noexcept;

  std::unique_ptr<Impl> impl_;
  std::string endpoint_;
  std::thread thread_;
};

}  // namespace stepmod::enip

#pragma once
// Commissioning under the lease: one connection at a time (the "operator") may take the lease,
// only while no PLC is in control (its heartbeat quiet for `plc_quiet`, or reported stale by the
// daemon); then its commands run through the plc/ dialect. The deadman: the lease is renewed
// only while the operator's keep-alives arrive (at least every `keepalive_limit`); when they
// stop (tab closed, focus lost, network gone) it is no longer renewed and the daemon stops the
// axes at its expiry (at most 500 ms). Killing stepmod-web stops the renewal the same way.
// A lease held by another tool is left alone (the take is refused with its pid), and a stop
// command works from any page without the lease (a stop is never refused).
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "ipc/client.hpp"
#include "ipc/lease.hpp"
#include "plc/shm_port.hpp"
#include "web/controls.hpp"
#include "web/sampler.hpp"
#include "web/sim_inputs.hpp"

namespace stepmod::web {

class Commander {
 public:
  struct Options {
    std::chrono::milliseconds plc_quiet{1000};
    std::chrono::milliseconds keepalive_limit{250};
  };
  Commander(const std::string& module_name, const Sampler& sampler, Options opt);
  ~Commander();
  Commander(const Commander&) = delete;
  Commander& operator=(const Commander&) = delete;

  // One request of connection `conn` ({"op": "take" | "release" | "keepalive" | "cmd", ...});
  // the reply to send back (keep-alives get none: null). A "cmd" needs the lease, but "stop";
  // "force_input" forces an input of the simulated machine (sim_inputs.hpp).
  nlohmann::json handle(const nlohmann::json& req, std::uintptr_t conn);
  // The connection is gone: if it was the operator, the lease is no longer renewed.
  void disconnected(std::uintptr_t conn);

 private:
  nlohmann::json take(std::uintptr_t conn);
  nlohmann::json release(std::uintptr_t conn);
  nlohmann::json command(const nlohmann::json& req, std::uintptr_t conn);
  void deadman_loop();

  ipc::Client client_;
  plc::ShmPort port_;  // without the PLC heartbeat: a lease holder is no PLC
  ipc::Lease lease_;
  const Sampler& sampler_;
  Options opt_;
  std::unique_ptr<Controls> controls_;
  SimInputs sim_;  // the simulated machine's inputs ("force_input"), where there is one

  std::mutex m_;  // guards everything below and serialises the plc/ calls
  std::uintptr_t operator_ = 0;
  std::chrono::steady_clock::time_point last_keepalive_{};
  bool renewing_ = false;  // the deadman renewed at its last turn (its log says when it stops)
  bool stop_ = false;
  std::condition_variable cv_;
  std::thread deadman_;
};

}  // namespace stepmod::web

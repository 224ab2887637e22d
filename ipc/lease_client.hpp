#pragma once
// The tool's side of the commissioning lease (INTERFACE.md 3.5, docs/commissioning.md): a tool
// that drives the module without a PLC (stepmodctl --wait, a browser console) holds the lease
// while it waits on its motion, so that the daemon stops the axes if the tool dies or hangs: the
// deadman a PLC's heartbeat gives. While held, a thread of this object renews it every 50 ms,
// keeping the expiry 400 ms ahead (the contract: at most 500 ms ahead, renewed at least every
// 100 ms). The holder must not bump the PLC heartbeat (that is a PLC's: health bit 7).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>

#include "ipc/client.hpp"

namespace stepmod::ipc {

class LeaseClient {
 public:
  static constexpr std::chrono::milliseconds kAhead{400};
  static constexpr std::chrono::milliseconds kRenewEvery{50};

  // `pid`: the holder id written into the image (this process' by default).
  explicit LeaseClient(Client& client, std::uint32_t pid = 0);
  ~LeaseClient();  // releases
  LeaseClient(const LeaseClient&) = delete;
  LeaseClient& operator=(const LeaseClient&) = delete;

  enum class Take : std::uint8_t {
    kTaken,         // held from now on, renewed until release()
    kPlcInControl,  // the PLC heartbeat moved within `quiet` (and is not reported stale)
    kHeldByOther,   // another tool holds it
  };
  // Takes the lease (compare-and-swap from 0) if no PLC is in control: the daemon reports the
  // heartbeat stale (health bit 1, after [module] plc_timeout_ms), or the heartbeat does not
  // change for `quiet` (watched here; the contract's 1 s when plc_timeout_ms is 0).
  Take take(std::chrono::milliseconds quiet = std::chrono::milliseconds(1000));
  // Gives the lease back (writes 0 if still ours) and stops renewing. Idempotent.
  void release();
  // Ours, as far as the image says (the daemon frees an expired lease).
  bool held() const noexcept;
  std::uint32_t pid() const noexcept { return pid_; }

 private:
  bool plc_quiet(std::chrono::milliseconds quiet) const;
  void renew() noexcept;
  void renew_loop();

  Client& client_;
  stepmod_image_t& img_;
  std::uint32_t pid_;
  std::mutex m_;
  std::condition_variable cv_;
  bool stop_ = false;
  bool taken_ = false;
  std::thread renewer_;
};

}  // namespace stepmod::ipc

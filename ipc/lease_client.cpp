#include "ipc/lease_client.hpp"

#include <unistd.h>

namespace stepmod::ipc {

LeaseClient::LeaseClient(Client& client, std::uint32_t pid)
    : client_(client),
      img_(client.writable_image()),
      pid_(pid != 0 ? pid : static_cast<std::uint32_t>(::getpid())) {}

LeaseClient::~LeaseClient() {
  release();
}

bool LeaseClient::plc_quiet(std::chrono::milliseconds quiet) const {
  if (client_.read_health().flags & STEPMOD_HEALTH_PLC_STALE) return true;
  const std::uint64_t hb = client_.heartbeat_value();
  const auto end = std::chrono::steady_clock::now() + quiet;
  while (std::chrono::steady_clock::now() < end) {
    if (client_.heartbeat_value() != hb) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return client_.heartbeat_value() == hb;
}

void LeaseClient::renew() noexcept {
  const auto expiry =
      stepmod_monotonic_ns() + std::chrono::duration_cast<std::chrono::nanoseconds>(kAhead).count();
  __atomic_store_n(&img_.lease_expiry_ns, static_cast<std::uint64_t>(expiry), __ATOMIC_RELEASE);
}

LeaseClient::Take LeaseClient::take(std::chrono::milliseconds quiet) {
  if (taken_) return Take::kTaken;
  if (__atomic_load_n(&img_.lease_holder, __ATOMIC_ACQUIRE) != 0) return Take::kHeldByOther;
  if (!plc_quiet(quiet)) return Take::kPlcInControl;
  // The expiry first: the daemon reads it only once it sees a holder, and a losing taker's
  // write is overwritten by the winner's next renewal (both at most kAhead ahead).
  renew();
  std::uint32_t free = 0;
  if (!__atomic_compare_exchange_n(&img_.lease_holder, &free, pid_, false, __ATOMIC_ACQ_REL,
                                   __ATOMIC_ACQUIRE)) {
    return Take::kHeldByOther;
  }
  __atomic_fetch_add(&img_.lease_seq, 1u, __ATOMIC_RELEASE);
  renew();
  taken_ = true;
  stop_ = false;
  renewer_ = std::thread([this] { renew_loop(); });
  return Take::kTaken;
}

void LeaseClient::renew_loop() {
  std::unique_lock lock(m_);
  while (!cv_.wait_for(lock, kRenewEvery, [this] { return stop_; })) {
    if (!held()) return;  // the daemon freed it (expired): nothing to renew
    renew();
  }
}

void LeaseClient::release() {
  if (!taken_) return;
  {
    std::lock_guard lock(m_);
    stop_ = true;
  }
  cv_.notify_all();
  if (renewer_.joinable()) renewer_.join();
  std::uint32_t mine = pid_;
  __atomic_compare_exchange_n(&img_.lease_holder, &mine, 0u, false, __ATOMIC_ACQ_REL,
                              __ATOMIC_ACQUIRE);
  taken_ = false;
}

bool LeaseClient::held() const noexcept {
  return __atomic_load_n(&img_.lease_holder, __ATOMIC_ACQUIRE) == pid_;
}

}  // namespace stepmod::ipc

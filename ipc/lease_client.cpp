#include "ipc/lease_client.hpp"

#include <pthread.h>
#include <sched.h>

namespace stepmod::ipc {

LeaseClient::LeaseClient(Client& client, std::uint32_t pid)
    : client_(client), lease_(client, pid) {}

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

LeaseClient::Take LeaseClient::take(std::chrono::milliseconds quiet) {
  return start(0, quiet);
}

LeaseClient::Take LeaseClient::take_over(std::uint32_t from, std::chrono::milliseconds quiet) {
  return start(from, quiet);
}

LeaseClient::Take LeaseClient::start(std::uint32_t from, std::chrono::milliseconds quiet) {
  if (taken_) return Take::kTaken;
  const std::uint32_t holder = lease_.holder();
  if (holder != 0 && holder != from) return Take::kHeldByOther;
  if (!plc_quiet(quiet)) return Take::kPlcInControl;
  // From `from`, or from 0 if the lease was freed meanwhile (take_over(0) is take()).
  if (!lease_.take_over(from) && !(from != 0 && lease_.take())) return Take::kHeldByOther;
  taken_ = true;
  stop_ = false;
  renewer_ = std::thread([this] { renew_loop(); });
  // Set from here, before its first renewal (kRenewEvery away), so that take() reports it.
  sched_param sp{};
  sp.sched_priority = kRenewerPriority;
  renewer_realtime_ = pthread_setschedparam(renewer_.native_handle(), SCHED_FIFO, &sp) == 0;
  return Take::kTaken;
}

void LeaseClient::renew_loop() {
  std::unique_lock lock(m_);
  while (!cv_.wait_for(lock, kRenewEvery, [this] { return stop_; })) {
    if (!lease_.renew()) return;  // the daemon freed it (expired): nothing to renew
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
  lease_.release();
  taken_ = false;
  renewer_realtime_ = false;
}

}  // namespace stepmod::ipc

#include "ipc/lease.hpp"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <climits>

namespace stepmod::ipc {
namespace {
template <typename T>
T load(const T& field) {
  // std::atomic_ref needs a non-const object; the load does not write.
  return std::atomic_ref<T>(const_cast<T&>(field)).load(std::memory_order_acquire);
}
}  // namespace

Lease::Lease(Client& client, std::uint32_t holder)
    : holder_(client.writable_image().lease_holder),
      seq_(client.writable_image().lease_seq),
      expiry_(client.writable_image().lease_expiry_ns),
      id_(holder != 0 ? holder : static_cast<std::uint32_t>(::getpid())) {}

Lease::~Lease() {
  release();
}

void Lease::write_expiry() noexcept {
  const auto ahead = std::chrono::duration_cast<std::chrono::nanoseconds>(kAhead).count();
  expiry_.store(static_cast<std::uint64_t>(stepmod_monotonic_ns() + ahead),
                std::memory_order_release);
}

bool Lease::take() {
  if (held()) return renew();
  // The holder first: a taker that loses writes nothing, so the expiry stays the holder's own.
  // (Writing the expiry before the compare-and-swap let a page retrying "Take control" keep a
  // SIGKILLed holder's lease alive, and its axis moving, for as long as it retried.)
  std::uint32_t free = 0;
  if (!holder_.compare_exchange_strong(free, id_, std::memory_order_acq_rel)) return false;
  return complete_take();
}

bool Lease::take_over(std::uint32_t from) {
  if (from == 0) return take();
  if (from == id_) return renew();
  std::uint32_t expected = from;
  if (!holder_.compare_exchange_strong(expected, id_, std::memory_order_acq_rel)) return false;
  return complete_take();
}

bool Lease::complete_take() noexcept {
  // The expiry before the sequence: the daemon validates a take's expiry once it sees the new
  // sequence (its acquire load of the sequence comes before that of the expiry). Until then the
  // take is under way, and one that stays so for kLeaseMaxAheadNs is freed by the daemon.
  write_expiry();
  seq_.fetch_add(1, std::memory_order_acq_rel);
  return held();
}

bool Lease::renew() noexcept {
  if (!held()) return false;
  // Freed and taken by another tool between the check and the store, this expiry lands in the
  // new holder's lease: at most kAhead from now, and this process renews no more.
  write_expiry();
  return true;
}

void Lease::release() noexcept {
  std::uint32_t mine = id_;
  holder_.compare_exchange_strong(mine, 0, std::memory_order_acq_rel);
}

bool Lease::held() const noexcept {
  return holder_.load(std::memory_order_acquire) == id_;
}

std::uint32_t Lease::holder() const noexcept {
  return holder_.load(std::memory_order_acquire);
}

std::uint32_t Lease::holder_of(const stepmod_image_t& img) {
  return load(img.lease_holder);
}

std::uint64_t Lease::expiry_of(const stepmod_image_t& img) {
  return load(img.lease_expiry_ns);
}

bool Lease::process_running(std::uint32_t pid) noexcept {
  // Above INT_MAX the pid_t would be negative: kill() would address a process group.
  if (pid == 0 || pid > static_cast<std::uint32_t>(INT_MAX)) return false;
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

}  // namespace stepmod::ipc

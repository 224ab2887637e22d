#include "ipc/lease.hpp"

#include <unistd.h>

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
  // The expiry first: the daemon reads it only once it sees a holder, and a losing taker's
  // write is overwritten by the winner's next renewal (both at most kAhead ahead).
  write_expiry();
  std::uint32_t free = 0;
  if (!holder_.compare_exchange_strong(free, id_, std::memory_order_acq_rel)) return false;
  seq_.fetch_add(1, std::memory_order_acq_rel);
  write_expiry();
  return true;
}

bool Lease::renew() noexcept {
  if (!held()) return false;
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

}  // namespace stepmod::ipc

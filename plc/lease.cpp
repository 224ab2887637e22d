#include "plc/lease.hpp"

namespace stepmod::plc {
namespace {
template <typename T>
T load(const stepmod_image_t& img, std::uint32_t off) {
  // The image is shared memory written by other processes: read the field atomically.
  auto* p = reinterpret_cast<T*>(
      const_cast<unsigned char*>(reinterpret_cast<const unsigned char*>(&img)) + off);
  return std::atomic_ref<T>(*p).load(std::memory_order_acquire);
}
}  // namespace

Lease::Lease(ipc::Client& client, std::uint32_t holder)
    : base_(reinterpret_cast<unsigned char*>(&client.writable_image())), id_(holder) {}

Lease::~Lease() {
  release();
}

std::atomic_ref<std::uint32_t> Lease::holder_ref() const {
  return std::atomic_ref<std::uint32_t>(*reinterpret_cast<std::uint32_t*>(base_ + kOffHolder));
}
std::atomic_ref<std::uint32_t> Lease::seq_ref() const {
  return std::atomic_ref<std::uint32_t>(*reinterpret_cast<std::uint32_t*>(base_ + kOffSeq));
}
std::atomic_ref<std::uint64_t> Lease::expiry_ref() const {
  return std::atomic_ref<std::uint64_t>(*reinterpret_cast<std::uint64_t*>(base_ + kOffExpiry));
}

void Lease::write_expiry() {
  const auto ahead = std::chrono::duration_cast<std::chrono::nanoseconds>(kAhead).count();
  expiry_ref().store(static_cast<std::uint64_t>(stepmod_monotonic_ns() + ahead),
                     std::memory_order_release);
}

bool Lease::take() {
  if (held()) return renew();
  // The expiry first: the daemon reads it only once it sees a holder.
  write_expiry();
  std::uint32_t free = 0;
  if (!holder_ref().compare_exchange_strong(free, id_, std::memory_order_acq_rel)) return false;
  seq_ref().fetch_add(1, std::memory_order_acq_rel);
  write_expiry();
  return true;
}

bool Lease::renew() {
  if (!held()) return false;
  write_expiry();
  return true;
}

void Lease::release() {
  std::uint32_t mine = id_;
  holder_ref().compare_exchange_strong(mine, 0, std::memory_order_acq_rel);
}

bool Lease::held() const {
  return holder_ref().load(std::memory_order_acquire) == id_;
}

std::uint32_t Lease::holder() const {
  return holder_ref().load(std::memory_order_acquire);
}

std::uint32_t Lease::holder_of(const stepmod_image_t& img) {
  return load<std::uint32_t>(img, kOffHolder);
}

std::uint64_t Lease::expiry_of(const stepmod_image_t& img) {
  return load<std::uint64_t>(img, kOffExpiry);
}

}  // namespace stepmod::plc

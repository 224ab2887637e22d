#include "ipc/lease_watch.hpp"

namespace stepmod::ipc {

LeaseWatch::Event LeaseWatch::scan(ShmImage& image, std::uint64_t heartbeat, Nanos now) noexcept {
  Event e;
  const ShmImage::Lease l = image.lease();
  e.holder = l.holder;
  if (l.holder != holder_ || (l.holder != 0 && l.seq != seq_)) {
    if (holder_ != 0) e.released = true;  // released (or released and taken again)
    if (l.holder != 0) {
      e.taken = true;
      heartbeat_ = heartbeat;
      flags_ &= ~(STEPMOD_HEALTH_LEASE_EXPIRED | STEPMOD_HEALTH_LEASE_CONFLICT);
    } else {
      flags_ &= ~STEPMOD_HEALTH_LEASE_CONFLICT;
    }
    holder_ = l.holder;
    seq_ = l.seq;
  }
  if (holder_ == 0) {
    // Bit 6 lasts until a PLC (its heartbeat) or a new lease takes over.
    if ((flags_ & STEPMOD_HEALTH_LEASE_EXPIRED) && heartbeat != heartbeat_) {
      flags_ &= ~STEPMOD_HEALTH_LEASE_EXPIRED;
    }
    return e;
  }
  if (heartbeat != heartbeat_ && !(flags_ & STEPMOD_HEALTH_LEASE_CONFLICT)) {
    flags_ |= STEPMOD_HEALTH_LEASE_CONFLICT;
    e.conflict = true;
  }
  if (now > l.expiry_ns && image.free_lease(holder_)) {
    e.expired = true;
    e.released = false;
    flags_ = (flags_ & ~STEPMOD_HEALTH_LEASE_CONFLICT) | STEPMOD_HEALTH_LEASE_EXPIRED;
    heartbeat_ = heartbeat;
    holder_ = 0;
  }
  return e;
}

}  // namespace stepmod::ipc

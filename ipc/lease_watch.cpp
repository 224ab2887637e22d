#include "ipc/lease_watch.hpp"

#include <algorithm>

namespace stepmod::ipc {

LeaseWatch::Event LeaseWatch::scan(ShmImage& image, std::uint64_t heartbeat, Nanos now) noexcept {
  Event e;
  const ShmImage::Lease l = image.lease();
  e.holder = l.holder;
  held_until_ = 0;
  if (l.holder == 0) {
    free_seen(l, heartbeat, e);
    return e;
  }
  if ((l.holder != holder_ || l.seq != seq_) && !follow_take(image, l, heartbeat, now, e)) {
    return e;
  }
  if (heartbeat != heartbeat_ && !(flags_ & STEPMOD_HEALTH_LEASE_CONFLICT)) {
    flags_ |= STEPMOD_HEALTH_LEASE_CONFLICT;
    e.conflict = true;
  }
  judge_expiry(image, l, heartbeat, now, e);
  return e;
}

void LeaseWatch::free_seen(const ShmImage::Lease& l, std::uint64_t heartbeat, Event& e) noexcept {
  if (holder_ != 0) e.released = true;
  holder_ = 0;
  pending_ = 0;
  replaced_ = 0;
  seq_ = l.seq;
  flags_ &= ~STEPMOD_HEALTH_LEASE_CONFLICT;
  // Bit 6 lasts until a PLC (its heartbeat) or a new lease takes over.
  if ((flags_ & STEPMOD_HEALTH_LEASE_EXPIRED) && heartbeat != heartbeat_) {
    flags_ &= ~STEPMOD_HEALTH_LEASE_EXPIRED;
  }
}

bool LeaseWatch::follow_take(ShmImage& image, const ShmImage::Lease& l, std::uint64_t heartbeat,
                             Nanos now, Event& e) noexcept {
  if (l.seq == seq_) {
    // A new holder without the sequence increment that ends a take: the taker is between its
    // compare-and-swap and its expiry, so that expiry is not its own yet. Nothing is held (the
    // heartbeat timeout applies) until the take completes, for kMaxAhead at most.
    if (holder_ != 0) {
      replaced_ = holder_;
      holder_ = 0;
      flags_ &= ~STEPMOD_HEALTH_LEASE_CONFLICT;
    }
    if (pending_ != l.holder) {
      pending_ = l.holder;
      pending_since_ = now;
    }
    if (now - pending_since_ > kMaxAhead) {
      expire(image, l.holder, heartbeat, Cause::kIncompleteTake, e);
    }
    return false;
  }
  e.taken = true;
  const std::uint32_t before = holder_ != 0 ? holder_ : replaced_;
  if (before != 0 && before != l.holder) {
    e.taken_from = before;
  } else if (holder_ != 0) {
    e.released = true;  // released and taken again by the same holder
  }
  holder_ = l.holder;
  seq_ = l.seq;
  pending_ = 0;
  replaced_ = 0;
  heartbeat_ = heartbeat;
  flags_ &= ~(STEPMOD_HEALTH_LEASE_EXPIRED | STEPMOD_HEALTH_LEASE_CONFLICT);
  return true;
}

void LeaseWatch::judge_expiry(ShmImage& image, const ShmImage::Lease& l, std::uint64_t heartbeat,
                              Nanos now, Event& e) noexcept {
  // The expiry is a u64 a tool wrote, read as i64: 2^64-1 is -1 (passed), 2^63-1 and
  // CLOCK_REALTIME values are far ahead. Compared before subtracting, which cannot overflow then.
  if (l.expiry_ns < now) {
    expire(image, holder_, heartbeat, Cause::kPassed, e);
  } else if (l.expiry_ns - now > kMaxAhead + kLeaseClockSlackNs) {
    expire(image, holder_, heartbeat, Cause::kTooFarAhead, e);
    e.ahead = l.expiry_ns - now;
  } else {
    held_until_ = std::min(l.expiry_ns, now + kMaxAhead);
  }
}

void LeaseWatch::expire(ShmImage& image, std::uint32_t holder, std::uint64_t heartbeat, Cause cause,
                        Event& e) noexcept {
  // A release or a take in between wins; the next scan sees it.
  if (!image.free_lease(holder)) return;
  e.expired = true;
  e.released = false;
  e.holder = holder;
  e.cause = cause;
  flags_ = (flags_ & ~STEPMOD_HEALTH_LEASE_CONFLICT) | STEPMOD_HEALTH_LEASE_EXPIRED;
  heartbeat_ = heartbeat;
  holder_ = 0;
  pending_ = 0;
  replaced_ = 0;
}

}  // namespace stepmod::ipc

#pragma once
// The daemon's side of the commissioning lease (docs/interface.md 3.5, docs/commissioning.md), one
// call per scan on the control thread: whether a tool holds the lease (the heartbeat timeout is
// then not applied, until the expiry at most), whether it expired without release (every moving
// axis stops: health bit 6) and whether a PLC heartbeat moved while it was held (two writers:
// health bit 7).
//
// Only what a live holder can have written keeps a lease (issue 29): an expiry that has passed,
// one more than kLeaseMaxAheadNs ahead of this clock (no holder writes that: a corrupted word, a
// CLOCK_REALTIME value, 2^63-1) and a holder whose take never completes (written without the
// sequence increment that ends a take, for kLeaseMaxAheadNs) all expire.
#include <cstdint>

#include "core/clock.hpp"
#include "ipc/lease_limits.hpp"
#include "ipc/shm_image.hpp"

namespace stepmod::ipc {

class LeaseWatch {
 public:
  static constexpr Nanos kMaxAhead = kLeaseMaxAheadNs;

  enum class Cause : std::uint8_t {
    kNone,
    kPassed,          // the expiry passed without a renewal: the holder died or hangs
    kTooFarAhead,     // the expiry is further ahead than any live holder writes it
    kIncompleteTake,  // a holder without its take's sequence increment for kMaxAhead
  };

  struct Event {
    bool taken = false;     // a tool took the lease at this scan
    bool released = false;  // its holder released it at this scan
    bool expired = false;   // it expired at this scan: stop every axis (the daemon freed it)
    bool conflict = false;  // the PLC heartbeat moved during the lease, first time at this scan
    std::uint32_t holder = 0;
    // A take that replaced this holder with no release seen in between (stepmodctl --steal).
    std::uint32_t taken_from = 0;
    Cause cause = Cause::kNone;  // why it expired
    Nanos ahead = 0;             // kTooFarAhead: how far ahead the expiry was
  };

  // `image`: where the lease lives; `heartbeat`: the PLC heartbeat of this scan.
  Event scan(ShmImage& image, std::uint64_t heartbeat, Nanos now) noexcept;

  bool held() const noexcept { return holder_ != 0; }
  // The held lease's expiry as this scan found it valid (0: none held): the PLC supervisor counts
  // the heartbeat fresh while a valid lease stands in for it.
  Nanos held_until() const noexcept { return held_until_; }
  // STEPMOD_HEALTH_LEASE_EXPIRED from an expiry until the next take or a heartbeat change;
  // STEPMOD_HEALTH_LEASE_CONFLICT while the lease in which the heartbeat moved is held.
  std::uint32_t flags() const noexcept { return flags_; }

 private:
  void free_seen(const ShmImage::Lease& l, std::uint64_t heartbeat, Event& e) noexcept;
  // A changed holder or sequence: false while a take is under way (nothing held yet).
  bool follow_take(ShmImage& image, const ShmImage::Lease& l, std::uint64_t heartbeat, Nanos now,
                   Event& e) noexcept;
  void judge_expiry(ShmImage& image, const ShmImage::Lease& l, std::uint64_t heartbeat, Nanos now,
                    Event& e) noexcept;
  void expire(ShmImage& image, std::uint32_t holder, std::uint64_t heartbeat, Cause cause,
              Event& e) noexcept;

  std::uint32_t holder_ = 0;    // the holder of a complete take, 0 = none
  std::uint32_t seq_ = 0;       // the lease sequence as last seen
  std::uint32_t pending_ = 0;   // a holder seen without its take's sequence increment ...
  Nanos pending_since_ = 0;     // ... since
  std::uint32_t replaced_ = 0;  // the complete holder a pending take replaced
  Nanos held_until_ = 0;
  std::uint64_t heartbeat_ = 0;  // at the take (held) or the expiry (bit 6)
  std::uint32_t flags_ = 0;
};

}  // namespace stepmod::ipc

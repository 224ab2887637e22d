#pragma once
// The daemon's side of the commissioning lease (INTERFACE.md 3.5, docs/commissioning.md), one
// call per scan on the control thread: whether a tool holds the lease (the heartbeat timeout is
// then not applied), whether it expired without release (every moving axis stops: health bit 6)
// and whether a PLC heartbeat moved while it was held (two writers: health bit 7).
#include <cstdint>

#include "core/clock.hpp"
#include "ipc/shm_image.hpp"

namespace stepmod::ipc {

class LeaseWatch {
 public:
  struct Event {
    bool taken = false;     // a tool took the lease at this scan
    bool released = false;  // its holder released it at this scan
    bool expired = false;   // it expired at this scan: stop every axis (the daemon freed it)
    bool conflict = false;  // the PLC heartbeat moved during the lease, first time at this scan
    std::uint32_t holder = 0;
  };

  // `image`: where the lease lives; `heartbeat`: the PLC heartbeat of this scan.
  Event scan(ShmImage& image, std::uint64_t heartbeat, Nanos now) noexcept;

  bool held() const noexcept { return holder_ != 0; }
  // STEPMOD_HEALTH_LEASE_EXPIRED from an expiry until the next take or a heartbeat change;
  // STEPMOD_HEALTH_LEASE_CONFLICT while the lease in which the heartbeat moved is held.
  std::uint32_t flags() const noexcept { return flags_; }

 private:
  std::uint32_t holder_ = 0;
  std::uint32_t seq_ = 0;
  std::uint64_t heartbeat_ = 0;  // at the take (held) or the expiry (bit 6)
  std::uint32_t flags_ = 0;
};

}  // namespace stepmod::ipc

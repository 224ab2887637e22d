#include "ipc/plc_supervisor.hpp"

#include "ipc/stepmod_image.h"

namespace stepmod::ipc {
namespace {
// A lease stands in for the heartbeat only with an expiry a live holder can have written.
bool lease_stands(const PlcSupervisor::Sample& s) noexcept {
  return s.lease_until != 0 && s.lease_until >= s.now && s.lease_until - s.now <= kLeaseMaxAheadNs;
}
}  // namespace

PlcSupervisor::PlcSupervisor(Nanos heartbeat_timeout) noexcept
    : heartbeat_timeout_(heartbeat_timeout > 0 ? heartbeat_timeout : 0),
      odd_timeout_(heartbeat_timeout > 0 ? heartbeat_timeout : kOddTimeoutWithoutHeartbeat) {}

// Heartbeat (docs/interface.md 3.2): stale while unchanged for the timeout, or at once while a
// fieldbus PLC is out of Run.
std::uint32_t PlcSupervisor::heartbeat_flags(const Sample& s) noexcept {
  std::uint32_t flags = 0;
  const bool lease = lease_stands(s);
  if (s.heartbeat != heartbeat_ || lease) {
    heartbeat_ = s.heartbeat;
    heartbeat_changed_ = s.now;
  }
  if (heartbeat_timeout_ > 0 && s.now - heartbeat_changed_ >= heartbeat_timeout_) {
    flags |= STEPMOD_HEALTH_PLC_STALE;
  }
  // A fieldbus PLC out of Run is a stale heartbeat at once, watched or not.
  not_in_run_ = s.plc_not_in_run && !lease;
  if (not_in_run_) flags |= STEPMOD_HEALTH_PLC_STALE;
  return flags;
}

const ImageWords& PlcSupervisor::scan(const Sample& s) noexcept {
  if (first_) {
    first_ = false;
    heartbeat_ = s.heartbeat;
    heartbeat_changed_ = s.now;
  }
  std::uint32_t flags = heartbeat_flags(s);

  // Output sequence: the same odd value for the timeout is a writer that never finished.
  if ((s.seq & 1u) != 0) {
    if (!odd_ || s.seq != odd_value_) {
      odd_ = true;
      odd_value_ = s.seq;
      odd_since_ = s.now;
    }
    if (s.now - odd_since_ >= odd_timeout_) flags |= STEPMOD_HEALTH_SEQ_STUCK;
  } else {
    odd_ = false;
  }

  // Seqlock bypass: the words changed under an unchanged sequence.
  if (s.snapshot_ok) {
    if (have_good_ && s.snapshot_seq == good_seq_ && !(s.words == good_)) {
      ++bypass_changes_;
      last_bypass_ = s.now;
      flags |= STEPMOD_HEALTH_SEQ_BYPASS;
    }
    have_good_ = true;
    good_seq_ = s.snapshot_seq;
    good_ = s.words;
  }
  if (bypass_changes_ > 0 && s.now - last_bypass_ < kBypassQuiet)
    flags |= STEPMOD_HEALTH_SEQ_BYPASS;

  started_ = flags & ~flags_;
  ended_ = flags_ & ~flags;
  flags_ = flags;

  const bool lost = (flags & (STEPMOD_HEALTH_PLC_STALE | STEPMOD_HEALTH_SEQ_STUCK)) != 0;
  tripped_ = lost && !lost_;
  if (tripped_) frozen_ = fed_;
  lost_ = lost;
  // Before any consistent snapshot the module sees zeros (a PLC that has written nothing yet).
  fed_ = lost_ ? frozen_ : (have_good_ ? good_ : ImageWords{});
  return fed_;
}

}  // namespace stepmod::ipc

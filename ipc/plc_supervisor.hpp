#pragma once
// Supervision of the PLC side of the image (docs/interface.md 3.1-3.3), one object in the control
// thread, fed once per scan with what the image showed. Pure logic (no clock, no logging), so it
// is tested scan by scan; the daemon logs the transitions it reports.
//
// Three conditions, each a health flag (STEPMOD_HEALTH_*), set while it lasts:
//  * PLC heartbeat stale (bit 1): [module] plc_timeout_ms on and the heartbeat unchanged that long,
//    or a fieldbus PLC out of Run (Sample::plc_not_in_run).
//  * Output sequence stuck odd (bit 2): the same odd sequence value for longer than the heartbeat
//    timeout, or 100 ms with the heartbeat watch off: a PLC that died in the middle of a write.
//  * Seqlock bypassed (bit 3): two consistent snapshots with the same sequence but different
//    words: someone writes the words without the sequence (old MSW with new LSW is then
//    possible). Set at such a change, cleared after kBypassQuiet without another one.
//
// The first two are the PLC lost. Design (issue 12 item 2): at the scan the PLC is lost the
// caller stops the module as for a PLC leaving Run mode (Personality::plc_stopped: every move
// stops, position invalid); while it stays lost the module keeps being scanned (status words go
// on being published, inputs followed) but with the last output words it was given before the
// loss, frozen, so no new 0->1 command edge can appear and nothing a dead or stalled PLC left in
// the image is acted on. When the PLC is back, the module gets the live words again and detects
// its edges against the frozen ones: a command bit that was already set before the loss and held
// through it is no new edge (the PLC must release and set it again, as after Program -> Run on
// the real module, where the backplane words of a PLC in Program mode are not acted on), while a
// bit the PLC set during or after the outage is one.  Feeding frozen words instead of zeros is
// deliberate: zeros would be a 1->0 edge of every level bit (a held manual move "released", the
// configuration-mode bit dropped, which leaves configuration mode) -- things the PLC never wrote.
#include <cstdint>

#include "core/clock.hpp"
#include "core/module_shape.hpp"
#include "ipc/lease_limits.hpp"
#include "ipc/stepmod_image.h"  // STEPMOD_HEALTH_* flags

namespace stepmod::ipc {

class PlcSupervisor {
 public:
  static constexpr Nanos kOddTimeoutWithoutHeartbeat = 100 * kNsPerMs;
  static constexpr Nanos kBypassQuiet = kNsPerSec;

  // `heartbeat_timeout`: [module] plc_timeout_ms in ns, 0 = heartbeat watch off.
  explicit PlcSupervisor(Nanos heartbeat_timeout) noexcept;

  // What one scan saw of the image.
  struct Sample {
    Nanos now = 0;
    std::uint64_t heartbeat = 0;
    std::uint32_t seq = 0;           // the output sequence as read at the scan (odd = mid-write)
    bool snapshot_ok = false;        // a consistent snapshot was taken ...
    std::uint32_t snapshot_seq = 0;  // ... under this (even) sequence value
    ImageWords words{};              // ... of these words
    // The expiry of a commissioning lease held at this scan (docs/interface.md 3.5; 0 = none), as
    // the daemon's lease watch found it valid: while it stands, the tool is the deadman and the
    // heartbeat counts as fresh. Only an expiry within [now, now + kLeaseMaxAheadNs] stands, so
    // no lease word (garbage, a far-off or passed expiry) holds off the heartbeat timeout for
    // longer than the 500 ms a live holder's lease lasts without renewal.
    Nanos lease_until = 0;
    // A fieldbus PLC that told us it left Run (the EtherNet/IP adapter's owner connection Idle,
    // timed out or closed: docs/ethernetip-design.md, "Where it sits in stepmod"). Treated
    // exactly as a stale heartbeat, whatever the heartbeat timeout is (also 0, the watch off),
    // until the PLC is back in Run. A standing lease holds it off as it holds off the timeout.
    bool plc_not_in_run = false;
  };

  // One scan. Returns the words the module is to scan this time (the live snapshot, the last
  // good one when no consistent snapshot could be taken, or the frozen ones while the PLC is
  // lost). Call once per scan, `now` non-decreasing.
  const ImageWords& scan(const Sample& s) noexcept;

  // Of the last scan():
  bool tripped() const noexcept { return tripped_; }  // the PLC was lost at this scan
  bool plc_lost() const noexcept { return lost_; }
  std::uint32_t flags() const noexcept { return flags_; }      // STEPMOD_HEALTH_PLC_STALE | ...
  std::uint32_t started() const noexcept { return started_; }  // flags set at this scan
  std::uint32_t ended() const noexcept { return ended_; }      // flags cleared at this scan

  // Diagnostics for the log lines.
  std::uint32_t stuck_seq() const noexcept { return odd_value_; }
  bool not_in_run() const noexcept { return not_in_run_; }  // the last sample's plc_not_in_run
  Nanos heartbeat_age(Nanos now) const noexcept { return now - heartbeat_changed_; }
  std::uint64_t bypass_changes() const noexcept { return bypass_changes_; }
  Nanos heartbeat_timeout() const noexcept { return heartbeat_timeout_; }
  Nanos odd_timeout() const noexcept { return odd_timeout_; }

 private:
  std::uint32_t heartbeat_flags(const Sample& s) noexcept;

  const Nanos heartbeat_timeout_;
  const Nanos odd_timeout_;
  bool first_ = true;
  std::uint64_t heartbeat_ = 0;
  Nanos heartbeat_changed_ = 0;
  bool odd_ = false;
  std::uint32_t odd_value_ = 0;
  Nanos odd_since_ = 0;
  bool have_good_ = false;
  std::uint32_t good_seq_ = 0;
  ImageWords good_{};    // last consistent snapshot
  ImageWords fed_{};     // last words given to the module
  ImageWords frozen_{};  // fed_ at the loss of the PLC
  Nanos last_bypass_ = 0;
  std::uint64_t bypass_changes_ = 0;
  bool lost_ = false;
  bool not_in_run_ = false;
  bool tripped_ = false;
  std::uint32_t flags_ = 0;
  std::uint32_t started_ = 0;
  std::uint32_t ended_ = 0;
};

}  // namespace stepmod::ipc

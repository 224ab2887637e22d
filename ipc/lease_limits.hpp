#pragma once
// The commissioning lease's one limit (docs/interface.md 3.5, docs/commissioning.md), shared by the
// tools' side (ipc/lease.hpp), the daemon's (ipc/lease_watch.hpp) and the PLC supervisor, so that
// the three cannot disagree on it.
#include "core/clock.hpp"

namespace stepmod::ipc {

// A holder keeps its expiry at most this far ahead of CLOCK_MONOTONIC (the contract). The daemon
// therefore takes an expiry further ahead for one no live holder can have written (a corrupted
// word, a CLOCK_REALTIME value, 2^63-1) and expires it at once; a take left incomplete this long
// (holder written, sequence never incremented: a taker that died in between) expires too; and a
// lease holds off the PLC heartbeat timeout for at most this long past the scan that saw it valid.
inline constexpr Nanos kLeaseMaxAheadNs = 500 * kNsPerMs;

// The daemon reads its clock at the top of a scan and the lease words later in it; a control
// thread preempted in between (a loaded machine, RT throttling) sees a live holder's fresh expiry
// further ahead than the holder wrote it. An expiry is "too far ahead" only past kLeaseMaxAheadNs
// and this slack (garbage is seconds ahead or more); the hold-off it grants stays capped at
// kLeaseMaxAheadNs from the scan.
inline constexpr Nanos kLeaseClockSlackNs = 150 * kNsPerMs;

}  // namespace stepmod::ipc

#pragma once
// The real-time setup of a step output's thread (rt/output_thread.hpp): memory locked, SCHED_FIFO
// at the configured priority, pinned to the configured CPU, stack prefaulted. Each step that is
// refused is recorded in the status, never fatal. Shared by the pulse thread and by the doctor's
// wake-up probe, so that the probe measures a thread set up exactly as the pulse thread is.
#include <cstddef>

#include "rt/output_thread.hpp"

namespace stepmod::rt {

// Call on the thread itself, before its loop. Returns true when the thread shares the machine's
// only CPU it may use (not pinned, one CPU allowed): the pulse thread then caps its spin.
bool setup_output_thread(const OutputThreadOptions& options, OutputThreadStatus& status) noexcept;

}  // namespace stepmod::rt

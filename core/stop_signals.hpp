#pragma once
// The signals that stop a stepmod program cleanly, the daemon and the console alike: SIGINT,
// SIGTERM and SIGHUP (the terminal closed: the same clean stop). They are blocked in every thread
// (threads created afterwards inherit the mask) and taken by one thread with sigwait or
// sigtimedwait, so no handler ever runs on another thread (the daemon's pulse thread above all).
#include <pthread.h>
#include <signal.h>

namespace stepmod {

inline sigset_t stop_signals() noexcept {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGHUP);
  return signals;
}

// Blocks the stop signals in the calling thread (call it before starting any other); the set,
// for the thread that waits for them.
inline sigset_t block_stop_signals() noexcept {
  const sigset_t signals = stop_signals();
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  return signals;
}

}  // namespace stepmod

#pragma once
// A cut: the planner replaces the edges it has already queued for one motion from a time on, so
// that a controlled stop (Hold, External input, encoder target) decelerates from its trigger
// instead of from the end of the ~4 ms of edges already in the ring.
//
//   planner thread                        pulse thread (every loop, before choosing an edge)
//   request(epoch E, t_c)  ── pending ──► decide: accept if no edge of E later than t_c has run
//   stops pushing this axis                     (then drop E's queued edges with t > t_c that
//   poll() == kAccepted:                        lack edge_flag::kReplacement as they reach the
//     replans from its step at t_c,             ring's head), else refuse (nothing is dropped)
//     pushes the new edges flagged
//     kReplacement
//   poll() == kRefused: stops the old way (from its newest planned step)
//
// Only the pulse thread knows which edges have run, so only it decides; the planner may withdraw
// a request the pulse thread has not decided yet (compare-and-swap, whoever is first wins).
// A new request waits until the previous cut's dropped edges have all left the ring (its
// replacement edges or a newer motion reached the head), so one cut is active at a time.
// Pulse-thread side: a few atomic loads and at most one compare-and-swap per loop; no locks.
#include <atomic>
#include <cstdint>

#include "core/clock.hpp"
#include "core/spsc_ring.hpp"
#include "rt/edge.hpp"

namespace stepmod::rt {

class EdgeCut {
 public:
  enum class Outcome : std::uint8_t { kNone, kPending, kAccepted, kRefused };

  // Planner thread. False (nothing requested) while an earlier request is still undecided.
  bool request(std::uint32_t epoch, Nanos t_c) noexcept {
    const std::uint32_t s = state_.load(std::memory_order_acquire);
    if ((s & kCodeMask) == kPendingCode) return false;
    epoch_.store(epoch, std::memory_order_relaxed);
    t_.store(t_c, std::memory_order_relaxed);
    state_.store(((s >> 2) + 1) << 2 | kPendingCode, std::memory_order_release);
    asked_ = true;
    return true;
  }
  // Planner thread: the decision on the newest request. kAccepted / kRefused are reported once;
  // after that (or a withdraw) it is kNone.
  Outcome poll() noexcept {
    if (!asked_) return Outcome::kNone;
    switch (state_.load(std::memory_order_acquire) & kCodeMask) {
      case kAcceptedCode:
        asked_ = false;
        return Outcome::kAccepted;
      case kRefusedCode:
        asked_ = false;
        return Outcome::kRefused;
      default:
        return Outcome::kPending;
    }
  }
  // Planner thread: take an undecided request back. False if the pulse thread decided first
  // (poll() then tells what it decided).
  bool withdraw() noexcept {
    std::uint32_t s = state_.load(std::memory_order_acquire);
    if (!asked_ || (s & kCodeMask) != kPendingCode) return false;
    if (!state_.compare_exchange_strong(s, (s & ~kCodeMask) | kIdle, std::memory_order_acq_rel)) {
      return false;
    }
    asked_ = false;
    return true;
  }

  // Pulse thread, each loop before it looks at the ring's head: decides a pending request and
  // drops the cut motion's replaced edges at the head.
  void before_next(SpscRing<Edge>& ring) noexcept {
    std::uint32_t s = state_.load(std::memory_order_acquire);
    if ((s & kCodeMask) == kPendingCode && cut_epoch_ == 0) {
      const std::uint32_t epoch = epoch_.load(std::memory_order_relaxed);
      const Nanos t = t_.load(std::memory_order_relaxed);
      // Every edge at or before t stays; so the cut is exact only if none after t has run.
      const bool ok = !(ran_epoch_ == epoch && ran_t_ > t);
      const std::uint32_t decided = (s & ~kCodeMask) | (ok ? kAcceptedCode : kRefusedCode);
      if (state_.compare_exchange_strong(s, decided, std::memory_order_acq_rel) && ok) {
        cut_epoch_ = epoch;
        cut_t_ = t;
      }
    }
    if (cut_epoch_ == 0) return;
    for (const Edge* e = ring.peek(); e != nullptr; e = ring.peek()) {
      if ((e->flags & edge_flag::kMotion) == 0 || e->epoch < cut_epoch_) return;
      if (e->epoch > cut_epoch_ || (e->flags & edge_flag::kReplacement) != 0) {
        cut_epoch_ = 0;  // every replaced edge was ahead of these: the cut is complete
        return;
      }
      if (e->t <= cut_t_) return;
      ring.pop();
    }
  }

  // Pulse thread, after executing `e`: remembers how far the motions have run.
  void executed(const Edge& e) noexcept {
    if ((e.flags & edge_flag::kMotion) == 0) return;
    ran_epoch_ = e.epoch;
    ran_t_ = e.t;
  }

 private:
  // state_ = sequence << 2 | code; the sequence makes every request's decision distinct.
  static constexpr std::uint32_t kCodeMask = 3;
  static constexpr std::uint32_t kIdle = 0, kPendingCode = 1, kAcceptedCode = 2, kRefusedCode = 3;
  std::atomic<std::uint32_t> state_{0};
  std::atomic<std::uint32_t> epoch_{0};  // written before a request's state_ (release)
  std::atomic<Nanos> t_{0};

  bool asked_ = false;  // planner thread only: a request whose outcome was not reported yet

  // Pulse thread only.
  std::uint32_t ran_epoch_ = 0;  // the newest executed motion edge: its epoch and time
  Nanos ran_t_ = 0;
  std::uint32_t cut_epoch_ = 0;  // the accepted cut being applied (0: none)
  Nanos cut_t_ = 0;
};

}  // namespace stepmod::rt

#include "doctor/wake_probe.hpp"

#include <atomic>
#include <cmath>
#include <thread>

#include "rt/deadline_sleep.hpp"
#include "rt/thread_setup.hpp"

namespace stepmod::doctor {

void WakeLatencies::add(Nanos late) noexcept {
  const Nanos us = late <= 0 ? 0 : late / kNsPerUs;
  ++counts_[us >= kBuckets ? kBuckets - 1 : static_cast<std::size_t>(us)];
  ++count_;
  if (late > worst_) worst_ = late;
}

Nanos WakeLatencies::percentile(double fraction) const noexcept {
  if (count_ == 0) return 0;
  const auto need = static_cast<std::uint64_t>(std::ceil(fraction * static_cast<double>(count_)));
  std::uint64_t seen = 0;
  for (unsigned b = 0; b < kBuckets; ++b) {
    seen += counts_[b];
    if (seen >= need) return b + 1 == kBuckets ? worst_ : static_cast<Nanos>(b + 1) * kNsPerUs;
  }
  return worst_;
}

namespace {

// The loop: no allocation, no lock, no logging; the sleep and the clock only.
void measure(const WakeProbeOptions& o, WakeLatencies& late) noexcept {
  std::atomic<std::uint32_t> never_rung{0};
  const Nanos end = monotonic_now() + o.duration;
  Nanos next = monotonic_now() + o.interval;
  while (next < end) {
    rt::futex_sleep_until(never_rung, 0, next);
    const Nanos now = monotonic_now();
    if (now < next) continue;  // a spurious wake-up: sleep again
    late.add(now - next);
    next += o.interval;
    if (next <= now) next = now + o.interval;  // woke later than a whole interval: resume
  }
}

}  // namespace

WakeProbeResult run_wake_probe(const WakeProbeOptions& options) {
  WakeProbeResult r;
  std::thread t([&] {
    rt::setup_output_thread(options.thread, r.status);
    r.status.started = true;
    measure(options, r.late);
  });
  t.join();
  return r;
}

}  // namespace stepmod::doctor

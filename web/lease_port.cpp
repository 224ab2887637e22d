#include "web/lease_port.hpp"

#include <thread>

namespace stepmod::web {
namespace {
using Clock = std::chrono::steady_clock;
constexpr auto kPoll = std::chrono::microseconds(500);
}  // namespace

ImageWords LeasePort::outputs() const {
  ImageWords w;
  client_.read_outputs(w);
  return w;
}

bool LeasePort::read_inputs(ImageWords& in) const {
  // On one CPU the module can be preempted inside its seqlock write: let it run, then retry.
  for (int i = 0; i < 200; ++i) {
    if (client_.read_inputs(in)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

bool LeasePort::wait_scans(unsigned n) {
  return client_.wait_scans(n, scan_timeout_);
}

void LeasePort::pass(std::chrono::nanoseconds d) {
  std::this_thread::sleep_for(d);
}

bool LeasePort::wait_inputs(const std::function<bool(const ImageWords&)>& done,
                            std::chrono::nanoseconds limit) {
  const auto deadline = Clock::now() + limit;
  for (;;) {
    ImageWords in;
    if (client_.read_inputs(in) && done(in)) return true;
    if (Clock::now() >= deadline) return false;
    std::this_thread::sleep_for(kPoll);
  }
}

}  // namespace stepmod::web

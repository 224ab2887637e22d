#include "plc/shm_port.hpp"

#include <thread>

namespace stepmod::plc {

namespace {
using Clock = std::chrono::steady_clock;
// How often a wait looks at the inputs and bumps the heartbeat.
constexpr auto kPoll = std::chrono::microseconds(500);
constexpr auto kHeartbeatSlice = std::chrono::milliseconds(10);
}  // namespace

std::optional<ReasonView> ShmPort::reason(unsigned unit) const {
  const stepmod_reason_t r = client_.read_reason(unit);
  return ReasonView{r.seq, r.item, std::string(r.text)};
}

ShmPort::ShmPort(ipc::Client& client, std::chrono::milliseconds scan_timeout, Heartbeat heartbeat)
    : client_(client), heartbeat_on_(heartbeat == Heartbeat::kOn), scan_timeout_(scan_timeout) {}

ImageWords ShmPort::outputs() const {
  ImageWords w;
  client_.read_outputs(w);
  return w;
}

bool ShmPort::read_inputs(ImageWords& in) const {
  // On one CPU the module can be preempted inside its seqlock write; a reader that only spins
  // never lets it finish. Let it run, then try again.
  for (int i = 0; i < 200; ++i) {
    if (client_.read_inputs(in)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

bool ShmPort::wait_scans(unsigned n) {
  beat();
  const std::uint64_t target = client_.scan_counter() + n;
  const auto deadline = Clock::now() + scan_timeout_;
  while (!client_.wait_scan_counter(target, std::chrono::milliseconds(50))) {
    beat();
    if (Clock::now() >= deadline) return false;
  }
  return true;
}

void ShmPort::pass(std::chrono::nanoseconds d) {
  const auto end = Clock::now() + d;
  for (auto now = Clock::now(); now < end; now = Clock::now()) {
    beat();
    std::this_thread::sleep_for(std::min<std::chrono::nanoseconds>(kHeartbeatSlice, end - now));
  }
}

bool ShmPort::wait_inputs(const std::function<bool(const ImageWords&)>& done,
                          std::chrono::nanoseconds limit) {
  const auto deadline = Clock::now() + limit;
  for (;;) {
    ImageWords in;
    if (client_.read_inputs(in) && done(in)) return true;
    if (Clock::now() >= deadline) return false;
    beat();
    std::this_thread::sleep_for(kPoll);
  }
}

}  // namespace stepmod::plc

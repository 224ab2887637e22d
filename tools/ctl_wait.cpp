#include "tools/ctl_wait.hpp"

#include <ostream>
#include <thread>

#include "config/config_keys.hpp"

namespace stepmod::tools::ctl {

namespace {
using Clock = std::chrono::steady_clock;
constexpr auto kPoll = std::chrono::milliseconds(2);
// A scan every [module] scan_us; this long without one, ten of the longest scan periods the key
// allows, is a daemon that stopped.
constexpr auto kStallLimit = std::chrono::milliseconds(1000);
static_assert(kStallLimit >= 10 * std::chrono::microseconds(config_key("module", "scan_us").max));
// Longer than the homing's pauses at rest (2 s, manuals ch. 4).
constexpr auto kHomingPause = std::chrono::milliseconds(2500);
}  // namespace

bool daemon_scanning(const ipc::Client& client, std::chrono::milliseconds limit) {
  return client.wait_scans(1, limit);
}

int wait_motion_end(ipc::Client& client, const std::vector<unsigned>& units, Motion kind,
                    std::chrono::nanoseconds limit, std::ostream& out, std::ostream& err) {
  // Two scans first: the status then shows the command that was just written.
  if (!client.wait_scans(2, kStallLimit)) {
    err << "stepmodctl: module '" << client.name() << "' does not scan (stepmodd stopped?)\n";
    return 3;
  }
  const auto deadline = Clock::now() + limit;
  std::uint64_t scans = client.scan_counter();
  auto scan_seen = Clock::now();
  auto idle_since = Clock::now();
  ImageWords in;
  for (;;) {
    const auto now = Clock::now();
    if (client.read_inputs(in)) {
      const auto s = summarize(client.type(), in);
      bool busy = false;
      for (unsigned u : units) {
        if (u >= s.size()) continue;
        // A homing rests 2 s between its segments without any motion bit: idle only counts once
        // an outcome shows, or after longer than such a pause.
        const bool outcome = s[u].move_complete || s[u].at_home || s[u].home_invalid ||
                             s[u].input_error || s[u].command_error || s[u].stopped || s[u].hold;
        const bool settled = outcome || kind == Motion::kMove || kind == Motion::kJog ||
                             now - idle_since > kHomingPause;
        busy = busy || s[u].moving() || !settled;
        if (s[u].moving()) idle_since = now;
      }
      if (!busy) break;
    }
    if (client.scan_counter() != scans) {
      scans = client.scan_counter();
      scan_seen = now;
    } else if (now - scan_seen > kStallLimit) {
      err << "stepmodctl: module '" << client.name() << "' stopped scanning while waiting\n";
      return 3;
    }
    if (now >= deadline) {
      err << "stepmodctl: still moving after "
          << std::chrono::duration_cast<std::chrono::milliseconds>(limit).count() << " ms\n";
      return 1;
    }
    std::this_thread::sleep_for(kPoll);
  }
  const auto s = summarize(client.type(), in);
  int rc = 0;
  const bool several = client.shape().axes > 1;
  for (unsigned u : units) {
    const MotionEnd end = judge_end(s[u], kind, client.read_reason(u));
    const std::string who =
        several ? std::string(client.shape().unit_noun) + " " + std::to_string(u + 1) + ": " : "";
    if (end.ok) {
      out << who << end.text << " at " << s[u].position << "\n";
    } else {
      err << "stepmodctl: " << who << "the motion " << end.text << " (position " << s[u].position
          << ")\n";
      rc = 1;
    }
  }
  return rc;
}

void warn_heartbeat_timeout(const ipc::Client& client, std::ostream& err) {
  if ((client.read_health().flags & STEPMOD_HEALTH_PLC_STALE) == 0) return;
  err << "stepmodctl: note: no PLC heartbeat, and stepmodd watches it ([module] "
         "plc_timeout_ms): this motion is stopped that long after stepmodctl exits. Add --wait "
         "to hold it under a commissioning lease (docs/commissioning.md)\n";
}

}  // namespace stepmod::tools::ctl

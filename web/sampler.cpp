#include "web/sampler.hpp"

#include <nlohmann/json.hpp>

#include "ipc/health.hpp"
#include "ipc/lease.hpp"
#include "registry/module_registry.hpp"
#include "web/image_json.hpp"
#include "web/reason.hpp"
#include "web/unit_state.hpp"

namespace stepmod::web {
namespace {
using Clock = std::chrono::steady_clock;
}  // namespace

Sampler::Sampler(const std::string& module_name, Publish publish, std::chrono::microseconds period,
                 std::chrono::milliseconds batch)
    : client_(module_name),
      sim_(module_name),
      publish_(std::move(publish)),
      period_(period),
      batch_(batch) {
  link_.heartbeat = client_.heartbeat_value();
  link_.heartbeat_changed = Clock::now();
  scan_ = client_.scan_counter();
  scan_changed_ = link_.heartbeat_changed;
  thread_ = std::thread([this] { run(); });
}

Sampler::~Sampler() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

PlcLink Sampler::plc_link() const {
  std::lock_guard lock(link_m_);
  return link_;
}

std::chrono::milliseconds Sampler::image_quiet() const {
  std::lock_guard lock(link_m_);
  return std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - scan_changed_);
}

void Sampler::take_sample(std::int64_t t_us) {
  ImageWords in;
  if (!client_.read_inputs(in)) return;  // a writer held the sequence: skip this sample
  last_in_ = in;
  Sample s{t_us, {0, 0}, {0, 0}};
  const unsigned units = client_.shape().axes;
  for (unsigned u = 0; u < units && u < 2; ++u) {
    const UnitRegisters r = registers_of(client_.type(), in, u);
    s.pos[u] = r.position;
    s.enc[u] = r.encoder;
  }
  pending_.push_back(s);
  samples_.fetch_add(1, std::memory_order_relaxed);
  const std::uint64_t hb = client_.heartbeat_value();
  const std::uint64_t scan = client_.scan_counter();
  std::lock_guard lock(link_m_);
  if (scan != scan_) {
    scan_ = scan;
    scan_changed_ = Clock::now();
  }
  if (hb != link_.heartbeat) {
    link_.heartbeat = hb;
    link_.heartbeat_changed = Clock::now();
  }
}

std::string Sampler::batch_json() {
  const ModuleType type = client_.type();
  const unsigned units = client_.shape().axes;
  nlohmann::json t = nlohmann::json::array();
  nlohmann::json pos = nlohmann::json::array();
  // The encoder samples, for the following error (position - encoder), where the module has an
  // encoder input; null where it has none.
  const bool encoder = client_.shape().terminals.encoder;
  nlohmann::json enc = encoder ? nlohmann::json::array() : nlohmann::json(nullptr);
  for (unsigned u = 0; u < units; ++u) pos.push_back(nlohmann::json::array());
  for (unsigned u = 0; u < units && encoder; ++u) enc.push_back(nlohmann::json::array());
  for (const Sample& s : pending_) {
    t.push_back(s.t_us);
    for (unsigned u = 0; u < units; ++u) pos[u].push_back(s.pos[u]);
    for (unsigned u = 0; u < units && encoder; ++u) enc[u].push_back(s.enc[u]);
  }
  nlohmann::json status = nlohmann::json::array();
  for (unsigned u = 0; u < units; ++u) {
    nlohmann::json j = unit_json(type, last_in_, u);
    j["reason"] = reason_json(client_.raw(), u, registry::row_of(type).rules->accel_word_unit);
    j["machine"] = unit_state_json(type, client_.read_unit_state(u));
    status.push_back(std::move(j));
  }
  const ipc::Health h = client_.read_health();
  const PlcLink link = plc_link();
  const auto quiet_ms =
      std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - link.heartbeat_changed);
  const auto image_ms = image_quiet();
  const bool gone = image_ms >= kDaemonGone;
  // Gone and its process no longer runs: stopped (or killed), not merely frozen (SIGSTOP, a hang).
  const bool stopped =
      gone && !ipc::Lease::process_running(static_cast<std::uint32_t>(client_.raw().owner_pid));
  // The image's strings (the reasons) come from another process: bad UTF-8 in them is written
  // as U+FFFD rather than thrown out of this thread.
  return nlohmann::json{
      {"type", "batch"},
      {"t_us", t},
      {"pos", pos},
      {"enc", enc},
      {"status", status},
      {"scan", client_.scan_counter()},
      {"sim", sim_.state()},
      {"daemon", {{"quiet_ms", image_ms.count()}, {"gone", gone}, {"stopped", stopped}}},
      {"health",
       {{"flags", h.flags},
        {"names", ipc::health_flag_names(h.flags)},
        {"late_faults", h.late_faults}}},
      {"plc",
       {{"heartbeat", link.heartbeat},
        {"quiet_ms", quiet_ms.count()},
        {"stale", (h.flags & STEPMOD_HEALTH_PLC_STALE) != 0}}},
      {"lease", {{"holder", ipc::Lease::holder_of(client_.raw())}}}}
      .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

void Sampler::run() {
  const auto start = Clock::now();
  auto next = start;
  auto next_batch = start + batch_;
  while (!stop_) {
    const auto now = Clock::now();
    take_sample(std::chrono::duration_cast<std::chrono::microseconds>(now - start).count());
    if (now >= next_batch) {
      {
        std::lock_guard lock(link_m_);
        link_.stale = (client_.read_health().flags & STEPMOD_HEALTH_PLC_STALE) != 0;
      }
      publish_(batch_json());
      pending_.clear();
      next_batch += batch_;
      if (next_batch < now) next_batch = now + batch_;
    }
    next += period_;
    if (next < now) next = now + period_;  // overrun (a loaded machine): no catch-up burst
    std::this_thread::sleep_until(next);
  }
}

}  // namespace stepmod::web

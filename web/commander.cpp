#include "web/commander.hpp"

#include <cstdio>
#include <stdexcept>

#include "registry/module_registry.hpp"
#include "web/reason.hpp"
#include "web/reason_help.hpp"

namespace stepmod::web {
namespace {
using Clock = std::chrono::steady_clock;

nlohmann::json reply(const std::string& op, bool ok, const std::string& message) {
  return {{"type", "reply"}, {"op", op}, {"ok", ok}, {"message", message}};
}

// A take refused because another tool holds the lease: who, and whether it still runs.
nlohmann::json held_by(std::uint32_t holder) {
  return reply("take", false,
               "refused: the lease is held by process " + std::to_string(holder) +
                   (ipc::Lease::process_running(holder)
                        ? ""
                        : " (not running: stepmodd frees its lease within 0.5 s)"));
}
}  // namespace

Commander::Commander(const std::string& module_name, const Sampler& sampler, Options opt)
    : client_(module_name),
      port_(client_, std::chrono::milliseconds(2000), plc::ShmPort::Heartbeat::kOff),
      lease_(client_),
      sampler_(sampler),
      opt_(opt),
      controls_(make_controls(port_)),
      sim_(module_name) {
  deadman_ = std::thread([this] { deadman_loop(); });
}

Commander::~Commander() {
  {
    std::lock_guard lock(m_);
    stop_ = true;
  }
  cv_.notify_all();
  deadman_.join();
  // A clean exit (SIGTERM) gives the lease back after letting go of any held jog; a crash
  // leaves it to expire, and the daemon stops the axes.
  if (lease_.held()) controls_->release_jogs();
  lease_.release();
}

void Commander::deadman_loop() {
  std::unique_lock lock(m_);
  while (!cv_.wait_for(lock, std::chrono::milliseconds(50), [this] { return stop_; })) {
    if (operator_ == 0) continue;
    const auto silent = Clock::now() - last_keepalive_;
    if (silent > opt_.keepalive_limit) {  // let it expire
      if (renewing_) {
        std::fprintf(stderr,
                     "stepmod-web: no keep-alive from the page for %lld ms: the lease is no "
                     "longer renewed\n",
                     static_cast<long long>(
                         std::chrono::duration_cast<std::chrono::milliseconds>(silent).count()));
      }
      renewing_ = false;
      continue;
    }
    renewing_ = lease_.renew();
    if (!renewing_) {
      std::fprintf(stderr, "stepmod-web: the daemon freed the lease (it expired)\n");
      operator_ = 0;
    }
  }
}

nlohmann::json Commander::take(std::uintptr_t conn) {
  if (operator_ != 0 && operator_ != conn) {
    return reply("take", false, "another page of this console holds the lease");
  }
  // Another tool's lease is not touched: not even by a take that would fail (issue 29: a page
  // retrying "Take control" must not push a dead holder's deadline).
  const std::uint32_t holder = lease_.holder();
  if (holder != 0 && holder != lease_.id()) return held_by(holder);
  const PlcLink link = sampler_.plc_link();
  const auto quiet = Clock::now() - link.heartbeat_changed;
  if (!link.stale && quiet < opt_.plc_quiet) {
    return reply(
        "take", false,
        "refused: a PLC is in control (its heartbeat changed " +
            std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(quiet).count()) +
            " ms ago)");
  }
  if (!lease_.take()) return held_by(lease_.holder());
  operator_ = conn;
  last_keepalive_ = Clock::now();
  renewing_ = true;
  return reply("take", true, "lease taken by process " + std::to_string(lease_.id()));
}

nlohmann::json Commander::release(std::uintptr_t conn) {
  if (operator_ != conn) return reply("release", false, "this page does not hold the lease");
  controls_->release_jogs();
  lease_.release();
  operator_ = 0;
  return reply("release", true, "lease released");
}

nlohmann::json Commander::command(const nlohmann::json& req, std::uintptr_t conn) {
  const std::string cmd = req.value("cmd", "");
  // An Immediate Stop is never refused: from any page, whoever holds the lease.
  if (cmd != "stop" && (operator_ != conn || !lease_.held())) {
    return reply(cmd, false, "refused: take the commissioning lease first");
  }
  try {
    if (cmd == "force_input") {
      sim_.force(req);
      return reply(cmd, true, "done");
    }
    const plc::Outcome o = controls_->run(req);
    // The plc/ library's message quotes the image's reason: its rates too in the form's unit.
    const std::int64_t accel_unit = registry::row_of(client_.type()).rules->accel_word_unit;
    nlohmann::json r = reply(cmd, o.ok, o.ok ? "done" : in_form_units(o.message, accel_unit));
    const unsigned unit = req.value("unit", 0u);
    r["reason"] = reason_json(client_.raw(), unit, accel_unit);
    return r;
  } catch (const std::invalid_argument& e) {
    return reply(cmd, false, std::string("refused: ") + e.what());
  }
}

nlohmann::json Commander::handle(const nlohmann::json& req, std::uintptr_t conn) {
  std::lock_guard lock(m_);
  const std::string op = req.value("op", "");
  if (op == "keepalive") {
    if (operator_ == conn) last_keepalive_ = Clock::now();
    return nullptr;
  }
  if (op == "take") return take(conn);
  if (op == "release") return release(conn);
  if (op == "cmd") return command(req, conn);
  return reply(op, false, "unknown op '" + op + "'");
}

void Commander::disconnected(std::uintptr_t conn) {
  std::lock_guard lock(m_);
  if (operator_ == conn) operator_ = 0;  // no more renewals: the daemon stops at the expiry
}

}  // namespace stepmod::web

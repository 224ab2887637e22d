#pragma once
// The PLC port over a running module's shared-memory image (ipc::Client), for every tool that
// writes the module's words. While it waits it is the PLC's heartbeat (docs/interface.md 3.2), as
// stepmodctl and the daemon tests drive the module as a PLC; a holder of the commissioning lease
// (ipc/lease.hpp: stepmodctl --wait, stepmod-web) is no PLC and uses it without the heartbeat:
// a heartbeat bumped while a lease is held reads as two writers to the daemon (health bit 7).
#include <chrono>

#include "ipc/client.hpp"
#include "plc/port.hpp"

namespace stepmod::plc {

class ShmPort final : public Port {
 public:
  enum class Heartbeat : bool { kOff = false, kOn = true };
  // `scan_timeout` bounds each wait_scans.
  explicit ShmPort(ipc::Client& client,
                   std::chrono::milliseconds scan_timeout = std::chrono::milliseconds(2000),
                   Heartbeat heartbeat = Heartbeat::kOn);

  ModuleType type() const override { return client_.type(); }
  ImageWords outputs() const override;
  void write_outputs(const ImageWords& out) override { client_.write_outputs(out); }
  void update_outputs(const std::function<void(ImageWords&)>& edit) override {
    client_.update_outputs(edit);
  }
  bool read_inputs(ImageWords& in) const override;
  std::optional<ReasonView> reason(unsigned unit) const override;
  // Off while the caller holds the commissioning lease (docs/interface.md 3.5).
  void set_heartbeat(bool on) noexcept { heartbeat_on_ = on; }
  bool wait_scans(unsigned n) override;
  void pass(std::chrono::nanoseconds d) override;
  bool wait_inputs(const std::function<bool(const ImageWords&)>& done,
                   std::chrono::nanoseconds limit) override;

  ipc::Client& client() noexcept { return client_; }

 private:
  ipc::Client& client_;
  bool heartbeat_on_ = true;
  void beat() {
    if (heartbeat_on_) client_.heartbeat();
  }
  std::chrono::milliseconds scan_timeout_;
};

}  // namespace stepmod::plc

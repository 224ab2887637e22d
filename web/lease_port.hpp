#pragma once
// The PLC port of a lease holder: the shared-memory image like plc::ShmPort, but without the PLC
// heartbeat. A commissioning tool is no PLC: its deadman is the lease (plc/lease.hpp), and a
// heartbeat bumped while a lease is held reads as two writers to the daemon.
#include <chrono>

#include "ipc/client.hpp"
#include "plc/port.hpp"

namespace stepmod::web {

class LeasePort final : public plc::Port {
 public:
  explicit LeasePort(ipc::Client& client,
                     std::chrono::milliseconds scan_timeout = std::chrono::milliseconds(2000))
      : client_(client), scan_timeout_(scan_timeout) {}

  ModuleType type() const override { return client_.type(); }
  ImageWords outputs() const override;
  void write_outputs(const ImageWords& out) override { client_.write_outputs(out); }
  void update_outputs(const std::function<void(ImageWords&)>& edit) override {
    client_.update_outputs(edit);
  }
  bool read_inputs(ImageWords& in) const override;
  bool wait_scans(unsigned n) override;
  void pass(std::chrono::nanoseconds d) override;
  bool wait_inputs(const std::function<bool(const ImageWords&)>& done,
                   std::chrono::nanoseconds limit) override;

 private:
  ipc::Client& client_;
  std::chrono::milliseconds scan_timeout_;
};

}  // namespace stepmod::web

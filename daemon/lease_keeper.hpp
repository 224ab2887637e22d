#pragma once
// The daemon's commissioning lease (docs/interface.md 3.5, docs/commissioning.md):
// ipc::LeaseWatch's verdicts acted on (an expired lease stops every moving axis) and logged.
#include "ipc/lease_watch.hpp"
#include "module/personality.hpp"

namespace stepmod::tools {

class LeaseKeeper {
 public:
  // One scan, before the supervisor's: returns the expiry of the lease held and valid at this
  // scan (0: none), for PlcSupervisor::Sample::lease_until (the heartbeat timeout is not applied
  // while it stands).
  Nanos scan(ipc::ShmImage& image, std::uint64_t heartbeat, Nanos now,
             module::Personality& personality);
  std::uint32_t flags() const noexcept { return watch_.flags(); }

 private:
  ipc::LeaseWatch watch_;
};

}  // namespace stepmod::tools

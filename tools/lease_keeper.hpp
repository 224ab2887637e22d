#pragma once
// The daemon's commissioning lease (INTERFACE.md 3.5, docs/commissioning.md): ipc::LeaseWatch's
// verdicts acted on (an expired lease stops every moving axis) and logged.
#include "ipc/lease_watch.hpp"
#include "module/personality.hpp"

namespace stepmod::tools {

class LeaseKeeper {
 public:
  // One scan, before the supervisor's: returns whether a lease is held (the heartbeat timeout
  // is then not applied).
  bool scan(ipc::ShmImage& image, std::uint64_t heartbeat, Nanos now,
            module::Personality& personality);
  std::uint32_t flags() const noexcept { return watch_.flags(); }

 private:
  ipc::LeaseWatch watch_;
};

}  // namespace stepmod::tools

#include "tools/lease_keeper.hpp"

#include <spdlog/spdlog.h>

#include "module/axis/error_items.hpp"

namespace stepmod::tools {

bool LeaseKeeper::scan(ipc::ShmImage& image, std::uint64_t heartbeat, Nanos now,
                       module::Personality& personality) {
  const ipc::LeaseWatch::Event e = watch_.scan(image, heartbeat, now);
  if (e.released) spdlog::info("commissioning lease released");
  if (e.taken) {
    spdlog::info(
        "commissioning lease taken by pid {}: the PLC heartbeat timeout is not applied while "
        "it is held",
        e.holder);
  }
  if (e.conflict) {
    spdlog::warn(
        "PLC heartbeat changed while pid {} holds the commissioning lease: two writers "
        "(health bit 7)",
        e.holder);
  }
  if (e.expired) {
    personality.stop_every_axis(module::axis::items::kPiLeaseExpired, now);
    spdlog::warn(
        "commissioning lease of pid {} expired without release: every moving axis stopped "
        "(immediate stop, position invalid; health bit 6)",
        e.holder);
  }
  return watch_.held();
}

}  // namespace stepmod::tools

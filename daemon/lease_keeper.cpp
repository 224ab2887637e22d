#include "daemon/lease_keeper.hpp"

#include <spdlog/spdlog.h>

#include "module/axis/error_items.hpp"

namespace stepmod::tools {
namespace {

void log_expiry(const ipc::LeaseWatch::Event& e) {
  using Cause = ipc::LeaseWatch::Cause;
  constexpr const char* kStopped =
      "every moving axis stopped (immediate stop, position invalid; health bit 6)";
  switch (e.cause) {
    case Cause::kTooFarAhead:
      spdlog::warn(
          "commissioning lease of pid {} expired without release: its expiry is {} ms ahead, "
          "more than the {} ms a live holder writes (garbage, or not CLOCK_MONOTONIC): {}",
          e.holder, e.ahead / kNsPerMs, ipc::kLeaseMaxAheadNs / kNsPerMs, kStopped);
      break;
    case Cause::kIncompleteTake:
      spdlog::warn(
          "commissioning lease of pid {} expired without release: its take never completed (no "
          "lease sequence increment within {} ms): {}",
          e.holder, ipc::kLeaseMaxAheadNs / kNsPerMs, kStopped);
      break;
    default:
      spdlog::warn("commissioning lease of pid {} expired without release: {}", e.holder, kStopped);
      break;
  }
}

}  // namespace

Nanos LeaseKeeper::scan(ipc::ShmImage& image, std::uint64_t heartbeat, Nanos now,
                        module::Personality& personality) {
  const ipc::LeaseWatch::Event e = watch_.scan(image, heartbeat, now);
  if (e.released) spdlog::info("commissioning lease released");
  if (e.taken_from != 0) {
    spdlog::warn(
        "commissioning lease of pid {} taken over by pid {} with no release in between "
        "(stepmodctl --steal): pid {} is the deadman from now on",
        e.taken_from, e.holder, e.holder);
  } else if (e.taken) {
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
    log_expiry(e);
  }
  return watch_.held_until();
}

}  // namespace stepmod::tools

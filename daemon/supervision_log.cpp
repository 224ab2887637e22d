#include "daemon/supervision_log.hpp"

#include <spdlog/spdlog.h>

namespace stepmod::tools {

void log_supervision(const ipc::PlcSupervisor& sup, Nanos now) {
  const std::uint32_t on = sup.started();
  const std::uint32_t off = sup.ended();
  if ((on | off) == 0) return;
  if ((on & STEPMOD_HEALTH_PLC_STALE) && sup.not_in_run()) {
    spdlog::warn(
        "EtherNet/IP: the owner PLC left Run (Idle, no O→T for its timeout, or Forward_Close): "
        "every axis stopped, position invalid; the output words are frozen until its next Run "
        "packet");
  } else if (on & STEPMOD_HEALTH_PLC_STALE) {
    spdlog::warn(
        "PLC heartbeat unchanged for {} ms: the PLC is treated as out of Run mode (every axis "
        "stopped, position invalid; the output words are frozen and not acted on until the "
        "heartbeat moves again)",
        sup.heartbeat_age(now) / kNsPerMs);
  }
  if (off & STEPMOD_HEALTH_PLC_STALE) {
    spdlog::info(
        "PLC heartbeat moves again (or the fieldbus PLC is back in Run): output words acted on "
        "again (a command bit held through the outage needs a new 0->1 edge)");
  }
  if (on & STEPMOD_HEALTH_SEQ_STUCK) {
    spdlog::warn(
        "output sequence left odd ({}) for {} ms: a PLC died in the middle of a write; treated "
        "as the PLC out of Run mode (every axis stopped, position invalid, words frozen)",
        sup.stuck_seq(), sup.odd_timeout() / kNsPerMs);
  }
  if (off & STEPMOD_HEALTH_SEQ_STUCK) {
    spdlog::info(
        "output sequence moves again: output words acted on again (a command bit held "
        "through the outage needs a new 0->1 edge)");
  }
  if (on & STEPMOD_HEALTH_SEQ_BYPASS) {
    spdlog::warn(
        "output words changed while the output sequence did not: a writer bypasses the seqlock "
        "(docs/interface.md 3.1); the module may act on torn words (an old MSW with a new LSW)");
  }
  if (off & STEPMOD_HEALTH_SEQ_BYPASS) {
    spdlog::info("no seqlock bypass for {} ms ({} bypassing change(s) seen in all)",
                 ipc::PlcSupervisor::kBypassQuiet / kNsPerMs, sup.bypass_changes());
  }
}

}  // namespace stepmod::tools

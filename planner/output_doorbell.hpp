#pragma once
// When the control thread rings the step output's doorbell (rt::StepOutput::ring): once a
// command has been submitted since it last looked, and once more when the planner has turned
// everything submitted into edges (Planner::served()). The first ring keeps the output polling
// for its awake time (rt/output_thread.hpp: 20 ms); a planner held off the CPU for longer than
// that (a loaded single-core board, a stalled VM) used to push its edges after the output had
// gone back to its quiet sleep (100 ms in the daemon), and a 3602's GPO line followed its status
// bit only that much later (issue 33: "both-off: GPO lines 25/15 read 0/1"). The second ring
// wakes the output for the edges that are now there, within a scan of the planner's service.
#include <cstdint>

#include "planner/planner.hpp"

namespace stepmod::planner {

class OutputDoorbell {
 public:
  explicit OutputDoorbell(const Planner& planner) noexcept
      : planner_(planner), wakes_(planner.wakes()), served_(planner.served()) {}

  // Control thread, after it may have submitted commands: true when the output should be rung.
  bool due() noexcept {
    const std::uint32_t w = planner_.wakes();
    const std::uint32_t s = planner_.served();
    if (w == wakes_ && s == served_) return false;
    wakes_ = w;
    served_ = s;
    return true;
  }

 private:
  const Planner& planner_;
  std::uint32_t wakes_;
  std::uint32_t served_;
};

}  // namespace stepmod::planner

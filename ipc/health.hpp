#pragma once
// The daemon health words of docs/interface.md section 3.3 (offsets 416, 420, and the extension at
// 424), as the control thread publishes them with the input image and clients read them.
#include <cstdint>
#include <string>
#include <vector>

#include "ipc/stepmod_image.h"

namespace stepmod::ipc {

struct Health {
  std::uint32_t flags = 0;          // STEPMOD_HEALTH_* bits
  std::uint32_t late_faults = 0;    // late-edge faults since the daemon started
  std::uint32_t worst_late_us = 0;  // largest lateness of such a fault, us (saturating)
  bool operator==(const Health&) const = default;
};

// "late-edge fault, PLC heartbeat stale" ... or "ok": the set flags by name, for logs and
// stepmodctl.
std::string health_flag_names(std::uint32_t flags);
// The same names one by one (none when healthy), for stepmodctl status --json.
std::vector<std::string> health_flag_list(std::uint32_t flags);

}  // namespace stepmod::ipc

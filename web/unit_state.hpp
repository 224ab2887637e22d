#pragma once
// What each axis/channel holds beyond its words (docs/interface.md 3.6), as the page shows it:
// the configuration it took (decoded into the form's fields by its module's view), each input
// line (wired, used, level, active) and the drive enable. Read from the image like the status:
// the daemon publishes it, the console only reads.
#include <nlohmann/json.hpp>
#include <optional>

#include "core/module_shape.hpp"
#include "ipc/stepmod_image.h"

namespace stepmod::web {

// {"config": null (none taken since the daemon started) | {"seq", "msw", "lsw" | "bits",
// "start_speed", ...}, "inputs": [{"name", "wired", "used", "level", "active"}, ...],
// "enable": {"wired", "asserted"}}; null for no consistent read.
nlohmann::json unit_state_json(ModuleType type, const std::optional<stepmod_unit_state_t>& s);

}  // namespace stepmod::web

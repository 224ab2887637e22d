#pragma once
// The [rt] table (docs/interface.md section 2): the pulse thread's priority and CPU and the
// late-edge guard's longest pause. A module file has it for its own daemon; a rack file has it
// once for every module (section 7), so both parsers read it here.
#include <toml++/toml.h>

#include "config/config.hpp"
#include "config/config_reader.hpp"

namespace stepmod::tools {

// Sets c.rt_priority, c.rt_cpu and c.late_limit_ns from `rt` (null: the keys' defaults).
void read_rt_section(const ConfigReader& reader, const toml::table* rt, Config& c);

}  // namespace stepmod::tools

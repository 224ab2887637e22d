#include "config/rt_section.hpp"

namespace stepmod::tools {

void read_rt_section(const ConfigReader& reader, const toml::table* rt, Config& c) {
  const std::string p = "rt";
  if (rt != nullptr) reader.check_keys(*rt, p, "rt");
  c.rt_priority = static_cast<int>(reader.get_int(rt, p, config_key("rt", "priority")));
  c.rt_cpu = static_cast<int>(reader.get_int(rt, p, config_key("rt", "cpu")));
  // The longest pause at any speed (late edges slip, never burst: docs/slip.md).
  c.late_limit_ns = reader.get_ns(rt, p, config_key("rt", "late_limit_us"));
}

}  // namespace stepmod::tools

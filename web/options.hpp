#pragma once
// stepmod-web's defaults, documented in docs/web-console.md and `stepmod-web --help`.
#include <string>

namespace stepmod::web {

inline constexpr unsigned kBasePort = 8610;
inline constexpr const char* kDefaultTokenFile = "/etc/stepmod/web-token";

// The instance's default port: 8610 + the number the module name ends with ("stepmod" → 8610,
// "press2" → 8612, "line17" → 8627), so that one board's instances do not collide; a name
// ending in more than 3 digits, or a port above 65535, is refused (use --port).
unsigned default_port(const std::string& module_name);

}  // namespace stepmod::web

#pragma once
// The tests of one table of the module file ([modbus], [ethernetip]): a minimal module (a 3601,
// one axis) with the table after it, and the ConfigError that gives.
#include <string>

#include "config/config.hpp"

namespace stepmod::tools {

inline constexpr const char* kBase = R"([module]
type = "3601"

[[axis]]
step = 17
dir = 27

)";  // the table starts on line 8

// The error of kBase + `table` ("FILE:LINE: key ...": the file is test.toml), "(accepted)" when
// none.
inline std::string error_of(const std::string& table) {
  try {
    parse_config(std::string(kBase) + table, "test.toml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(accepted)";
}

}  // namespace stepmod::tools

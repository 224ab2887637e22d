#pragma once
// A rack (docs/interface.md section 7): several modules in one stepmodd, sharing one pulse
// thread and one planner thread. A rack file names module files (section 2) and holds the one
// [rt] table of them all:
//   [rack]
//   modules = ["x.toml", "y.toml"]   # 1 … 16, relative to the rack file or absolute
//   [rt]                              # optional; section 2's keys and defaults
// A module file is a rack of one: stepmodd reads either through load_rack and runs one path.
#include <string>
#include <vector>

#include "config/config.hpp"

namespace stepmod::tools {

struct RackConfig {
  std::string file;             // the file stepmodd was given
  bool rack_file = false;       // a [rack] file (false: a module file, a rack of one)
  std::vector<Config> modules;  // in the file's order; each holds the rack's [rt] values
};

// A module file or a rack file; a rack's module files are read and checked, each on its own
// (section 2) and against each other (check_rack). Throws ConfigError naming the file and key.
RackConfig load_rack(const std::string& path);

// The rules between a rack's modules (section 7; load_rack refuses an [rt] table in a module
// file as it reads it): names and gpiod lines (chip + offset) used once, and modules that share a Modbus listen address with
// different unit ids and equal server keys. Throws ConfigError naming both files and keys.
void check_rack(const RackConfig& rack);

}  // namespace stepmod::tools

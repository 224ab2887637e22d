#pragma once
// stepmodctl's command line: what its options set (CtlOptions) and the sub-commands that are not
// module commands (a module command sets CtlOptions::cmd.verb when CLI11 parses it).
#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "config/config_keys.hpp"
#include "tools/ctl_command.hpp"

namespace stepmod::tools::ctl {

struct CtlOptions {
  std::string name{config_key("module", "name").text};  // the daemon's default [module] name
  int timeout_ms = 2000;
  unsigned axis_no = 0;             // --axis, 1-based; 0 = not given
  unsigned channel_no = 0;          // --channel, 1-based; 0 = not given
  CtlRequest cmd;                   // the module command
  bool wait = false;                // --wait of a motion command
  bool steal = false;               // --steal: take the commissioning lease over (logged)
  std::string gpo_state;            // gpo on|off
  bool brief = false;               // status / watch --brief
  bool json = false;                // status --json
  int interval_ms = 200;            // watch --interval
  std::string raw_word, raw_value;  // raw set WORD VALUE
  unsigned p_axis = 1;              // panel force|release AXIS INPUT [LEVEL]
  std::string p_input;
  int p_level = 0;
  std::vector<std::string> spool_paths;  // trace recover SPOOL... -o VCD [--keep]
  std::string recovered_vcd;
  bool keep_spools = false;
};

struct CtlSubcommands {
  CLI::App* status = nullptr;
  CLI::App* watch = nullptr;
  CLI::App* raw_get = nullptr;
  CLI::App* raw_set = nullptr;
  CLI::App* panel = nullptr;
  CLI::App* panel_force = nullptr;
  CLI::App* panel_release = nullptr;
  CLI::App* trace_recover = nullptr;
};

// Adds every option and sub-command to `app` (in --help order), bound to `o`.
CtlSubcommands define_cli(CLI::App& app, CtlOptions& o);

}  // namespace stepmod::tools::ctl

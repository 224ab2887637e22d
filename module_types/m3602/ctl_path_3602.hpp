#pragma once
// stepmodctl's 3602 interpolated moves (`path line|centre|radius|via`, `path wait`): the options
// as the manual's move (plc::PathMove3602), checked against the words that carry them before
// anything is written, then sent by module_types/m3602/plc_interp_3602 (data first, the command bits >= 10 ms later).
// Kept apart from ctl_3602.cpp (single-axis commands): a path drives both axes at once.
#include <chrono>

#include "module_types/m3602/plc_interp_3602.hpp"
#include "plc/port.hpp"
#include "tools/ctl_args.hpp"
#include "tools/ctl_command.hpp"

namespace stepmod::tools::ctl {

// The move the command describes; UsageError for what the 3602's words cannot carry or a
// method without its arguments.
plc::PathMove3602 path_move_3602(const CtlRequest& c, const ProfileLimits& limits);

// Runs `path ...` (Verb::kPath) or `path wait` (Verb::kPathWait) on a 3602.
plc::Outcome run_path_3602(const CtlRequest& c, plc::Port& port, std::chrono::milliseconds timeout,
                           const ProfileLimits& limits);

}  // namespace stepmod::tools::ctl

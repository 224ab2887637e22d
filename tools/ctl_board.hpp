#pragma once
// stepmodctl's board commands, which need no module running: `doctor` (what this board can do
// for the pulse thread, measured) and `isolate` (a CPU of its own for it). Their work is in
// doctor/; this is their command line.
#include <CLI/CLI.hpp>

#include <optional>

#include "doctor/doctor.hpp"
#include "doctor/isolate.hpp"

namespace stepmod::tools::ctl {

struct BoardCommands {
  doctor::DoctorOptions doctor;
  doctor::IsolateOptions isolate;
  CLI::App* doctor_cmd = nullptr;
  CLI::App* isolate_cmd = nullptr;
};

// Adds the sub-commands to `app`, bound to `b` (which must outlive the parse).
void add_board_commands(CLI::App& app, BoardCommands& b);
// The exit status of the board command parsed, or nullopt when none was.
std::optional<int> run_board_command(const BoardCommands& b);

}  // namespace stepmod::tools::ctl

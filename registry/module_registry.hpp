#pragma once
// The module types, one row each (model: LinuxCNC stepgen.c's master_lut, where a variant is a
// table row). A row holds everything that differs by module type above the words: its number and
// name, its image shape, its rules value (what the shared axis does differently), the factory of
// its personality, and how stepmodctl drives and shows it. Code that needs one of these for a
// type looks the row up here: nothing else switches on the module type.
//
// The image shapes themselves are written in core/module_shape.hpp (kModuleShapes), because
// ipc/, plc/ and the config checker sit below this library; the row repeats nothing, it reads the
// shape from there, and module_registry.cpp checks at compile time that the two lists agree.
#include <chrono>
#include <memory>
#include <span>
#include <sstream>
#include <string_view>
#include <vector>

#include "core/module_shape.hpp"
#include "ipc/client.hpp"
#include "module/axis/rules.hpp"
#include "module/personality.hpp"
#include "planner/motion_port.hpp"
#include "plc/port.hpp"
#include "plc/profile.hpp"
#include "tools/ctl_command.hpp"
#include "tools/ctl_summary.hpp"

namespace stepmod::registry {

// The personality over one motion port per axis (the row's shape.axes of them).
using MakePersonality = std::unique_ptr<module::Personality>(
    module::AxisIo& io, std::span<planner::MotionPort* const> axes);
// stepmodctl's dialect: a parsed command -> the plc/ calls (messages travel through `client`).
using RunCommand = plc::Outcome(const tools::ctl::Command& c, plc::Port& port, ipc::Client& client,
                                std::chrono::milliseconds timeout);
// stepmodctl status: the decoded input image, multi-line.
using FormatStatus = void(std::ostringstream& o, const ImageWords& in);
// Every axis/channel in a few words (stepmodctl --brief, --json, wait-idle, --wait).
using Summarize = std::vector<tools::ctl::AxisSummary>(const ImageWords& in);

struct ModuleTypeRow {
  ModuleType type;                         // its number, as the image header carries it
  std::string_view name;                   // as the config file ([module] type) writes it
  ModuleShape shape;                       // core/module_shape.hpp
  const module::axis::ModuleRules* rules;  // module/mXXXX/rules_XXXX.hpp
  MakePersonality* make_personality;       // module/mXXXX/module_XXXX.hpp
  RunCommand* run_command;                 // tools/ctl_XXXX.cpp
  FormatStatus* format_status;             // tools/ctl_status_XXXX.cpp
  Summarize* summarize;                    // tools/ctl_status_XXXX.cpp
};

// Every row, in kModuleShapes' order.
std::span<const ModuleTypeRow> module_type_rows() noexcept;

// The row of `type`. Throws std::invalid_argument for a number that is no module type (a
// ModuleType made from an unchecked number).
const ModuleTypeRow& row_of(ModuleType type);

// The personality for `type` over `axes` (one MotionPort per axis of the module); throws
// std::invalid_argument when the count is not the module's.
std::unique_ptr<module::Personality> make_personality(ModuleType type, module::AxisIo& io,
                                                      std::span<planner::MotionPort* const> axes);

}  // namespace stepmod::registry

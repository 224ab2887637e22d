#include "registry/module_registry.hpp"

#include <array>
#include <stdexcept>
#include <string>

#include "module_types/m3202/module_3202.hpp"
#include "module_types/m3202/rules_3202.hpp"
#include "module_types/m3601/module_3601.hpp"
#include "module_types/m3601/rules_3601.hpp"
#include "module_types/m3602/module_3602.hpp"
#include "module_types/m3602/rules_3602.hpp"
#include "tools/ctl_dialects.hpp"

namespace stepmod::registry {
namespace {

using planner::MotionPort;
using std::chrono::milliseconds;

// ---- one row per module type ----------------------------------------------------------------

constexpr ModuleTypeRow kRow3601{
    .type = ModuleType::k3601,
    .name = "3601",
    .shape = shape_of(ModuleType::k3601),
    .rules = &module::m3601::kRules3601,
    .make_personality = [](gpio::Backend& b,
                           std::span<MotionPort* const> a) -> std::unique_ptr<module::Personality> {
      return std::make_unique<module::m3601::Module3601>(b, *a[0]);
    },
    .run_command = [](const tools::ctl::Command& c, plc::Port& p, ipc::Client&,
                      milliseconds t) { return tools::ctl::run_3601(c, p, t); },
    .format_status = tools::ctl::format_status_3601,
    .summarize = tools::ctl::summarize_3601,
};

constexpr ModuleTypeRow kRow3602{
    .type = ModuleType::k3602,
    .name = "3602",
    .shape = shape_of(ModuleType::k3602),
    .rules = &module::m3602::kRules3602,
    .make_personality = [](gpio::Backend& b,
                           std::span<MotionPort* const> a) -> std::unique_ptr<module::Personality> {
      return std::make_unique<module::m3602::Module3602>(b, *a[0], *a[1]);
    },
    .run_command = [](const tools::ctl::Command& c, plc::Port& p, ipc::Client&,
                      milliseconds t) { return tools::ctl::run_3602(c, p, t); },
    .format_status = tools::ctl::format_status_3602,
    .summarize = tools::ctl::summarize_3602,
};

constexpr ModuleTypeRow kRow3202{
    .type = ModuleType::k3202,
    .name = "3202",
    .shape = shape_of(ModuleType::k3202),
    .rules = &module::m3202::kRules3202,
    .make_personality = [](gpio::Backend& b,
                           std::span<MotionPort* const> a) -> std::unique_ptr<module::Personality> {
      return std::make_unique<module::m3202::Module3202>(b, *a[0], *a[1]);
    },
    .run_command = tools::ctl::run_3202,
    .format_status = tools::ctl::format_status_3202,
    .summarize = tools::ctl::summarize_3202,
};

constexpr std::array kRows = {kRow3601, kRow3602, kRow3202};

// ---- the rows agree with the ground list of shapes and with themselves ------------------------

constexpr bool rows_match_shapes() {
  if (kRows.size() != kModuleShapes.size()) return false;
  for (std::size_t i = 0; i < kRows.size(); ++i) {
    const ModuleTypeRow& r = kRows[i];
    if (r.type != kModuleShapes[i].type || r.shape.axes != kModuleShapes[i].axes) return false;
    if (r.rules->type != r.type || module_type_from_name(r.name) != r.type) return false;
    // The config checker's terminals (core/) and the axis code's features (rules) agree.
    const AxisTerminals& io = kModuleShapes[i].terminals;
    if (io.encoder != r.rules->has_encoder || io.estop != r.rules->has_estop_input) return false;
    if (kModuleShapes[i].reason_digit == 0) return false;
  }
  return true;
}
static_assert(rows_match_shapes(), "a module type needs one row, in kModuleShapes' order");

}  // namespace

std::span<const ModuleTypeRow> module_type_rows() noexcept {
  return kRows;
}

const ModuleTypeRow& row_of(ModuleType type) {
  for (const ModuleTypeRow& r : kRows) {
    if (r.type == type) return r;
  }
  throw std::invalid_argument("unknown module type " + std::to_string(static_cast<unsigned>(type)));
}

std::unique_ptr<module::Personality> make_personality(ModuleType type, gpio::Backend& backend,
                                                      std::span<MotionPort* const> axes) {
  const ModuleTypeRow& row = row_of(type);
  if (axes.size() != row.shape.axes) {
    throw std::invalid_argument("module needs one motion port per axis");
  }
  return row.make_personality(backend, axes);
}

}  // namespace stepmod::registry

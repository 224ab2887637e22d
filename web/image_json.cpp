#include "web/image_json.hpp"

#include <unistd.h>

#include <chrono>

#include "registry/module_registry.hpp"
#include "web/module_views.hpp"
#include "web/reason_help.hpp"

namespace stepmod::web {

UnitRegisters registers_of(ModuleType type, const ImageWords& in, unsigned unit) {
  return view_of(type).registers(in, unit);
}

nlohmann::json unit_json(ModuleType type, const ImageWords& in, unsigned unit) {
  const ModuleView& view = view_of(type);
  const UnitRegisters r = view.registers(in, unit);
  return {{"unit", unit},
          {"words", view.status_words(in, unit)},
          {"position", r.position},
          {"encoder", r.encoder},
          {"capture", r.capture}};
}

nlohmann::json module_json(ModuleType type) {
  const ModuleShape shape = shape_of(type);
  const module::axis::ModuleRules& r = *registry::row_of(type).rules;
  const nlohmann::json cfg = view_of(type).config_bits();
  // The same ramp by default on every module: 100 steps/ms/s = 100,000 steps/s^2.
  const bool per_s2 = r.accel_word_unit == 1;
  return {{"type", static_cast<unsigned>(type)},
          {"units", shape.axes},
          {"unit_noun", shape.unit_noun},
          {"has_encoder", shape.terminals.encoder},
          {"config_bits", cfg},
          {"ranges",
           {{"speed_max", r.speed_max},
            {"starting_speed_min", r.starting_speed_min},
            {"starting_speed_max", r.starting_speed_max},
            {"accel_min", r.accel_min / r.accel_word_unit},
            {"accel_max", r.accel_max / r.accel_word_unit},
            {"accel_unit", per_s2 ? "steps/s²" : "steps/ms/s"},
            {"accel_default", per_s2 ? 100'000 : 100},
            {"target_min", r.target_min},
            {"target_max", r.target_max},
            {"homing_timeout_max", r.has_homing_timeout ? r.homing_timeout_max_s : 0}}}};
}

nlohmann::json hello_json(const std::string& name, ModuleType type) {
  static const auto started = std::chrono::duration_cast<std::chrono::milliseconds>(
                                  std::chrono::system_clock::now().time_since_epoch())
                                  .count();
  return {{"type", "hello"},
          {"name", name},
          {"module", module_json(type)},
          {"console", {{"pid", static_cast<std::int64_t>(getpid())}, {"started_ms", started}}},
          {"reasons", reason_table(type)}};
}

}  // namespace stepmod::web

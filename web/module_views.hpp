#pragma once
// The console's side of each module type, one row per type (the web counterpart of the registry
// row in registry/module_registry.hpp, which cannot depend on web/): how the page shows a unit's
// registers and status words, which configuration bits its form offers, and the controls that
// turn the page's commands into the module's plc/ calls. Each row is kViewOf<T>
// (web/module_view_of.hpp), pointing at the functions of its type's view_XXXX.cpp, and is
// collected by the generated module_types/view_rows.hpp. Code in web/ that needs one of these
// looks the row up here: nothing in web/ switches on the module type.
#include <memory>
#include <nlohmann/json.hpp>

#include "core/module_shape.hpp"
#include "plc/port.hpp"
#include "web/controls.hpp"
#include "web/image_json.hpp"

namespace stepmod::web {

struct ModuleView {
  ModuleType type;
  // Registers of `unit` (0-based axis/channel) decoded from the input words.
  UnitRegisters (*registers)(const ImageWords& in, unsigned unit);
  // The status words of `unit`, each with every named field (word_json, web/bit_json.hpp).
  nlohmann::json (*status_words)(const ImageWords& in, unsigned unit);
  // The configuration bits by name, as the page's form groups them ({"msw": ..., "lsw": ...}).
  nlohmann::json (*config_bits)();
  // The configuration a unit took, from its 8 output words of its last configuration scan
  // (docs/interface.md 3.6; word 0 = the unit's first): the form's fields ({"msw", "lsw"} or
  // {"bits"}, "start_speed", the 3602's "homing_timeout").
  nlohmann::json (*config_of)(const ImageWords& words);
  // The controls of the module behind `port` (module_types/mXXXX/view_XXXX.cpp).
  std::unique_ptr<Controls> (*make_controls)(plc::Port& port);
};

// The row of `type`. Throws std::invalid_argument for a number that is no module type.
const ModuleView& view_of(ModuleType type);

}  // namespace stepmod::web

#pragma once
// The module's input image as the console page shows it: per axis/channel every status bit by the
// manual's name (the module's bit tables, as stepmodctl status shows them), position, encoder and
// capture in steps; the configuration fields and ranges for the page's form.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "core/module_shape.hpp"

namespace stepmod::web {

// One unit's registers in steps (what the plot samples).
struct UnitRegisters {
  std::int64_t position = 0;
  std::int64_t encoder = 0;
  std::int64_t capture = 0;
};

// Registers of `unit` (0-based axis/channel) decoded from the input words.
UnitRegisters registers_of(ModuleType type, const ImageWords& in, unsigned unit);

// The status words of `unit` with every named field: [{"word": "Status Word MSW", "bits":
// [{"bit": 0, "name": "...", "value": 0}, ...]}, ...] plus the registers.
nlohmann::json unit_json(ModuleType type, const ImageWords& in, unsigned unit);

// What the page needs once: module type, units (and what the manual calls one: "unit_noun"),
// whether it has an encoder input, the configuration bits by name and the ranges of the manual's
// fields.
nlohmann::json module_json(ModuleType type);

// The page's first message (and /api/hello): {"type": "hello", "name", "module": module_json(),
// "console": {"pid", "started_ms"}, "reasons": reason_table()}. The console's process id is the
// lease holder the image shows while a page of this console holds it; pid and start time tell
// a page that reconnects whether stepmod-web restarted meanwhile (its lease and session gone).
nlohmann::json hello_json(const std::string& name, ModuleType type);

}  // namespace stepmod::web

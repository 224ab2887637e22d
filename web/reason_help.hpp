#pragma once
// What the page shows of an error reason beyond the image's 56-byte sentence: the item's
// condition in full (the item tables the daemon raises them from, module/axis/error_items.hpp
// and a module type's own, its registry row's own_items), what to do about it, and its anchor on the console's
// /reasons page (the same table as docs/error-reasons.md). Its sentence's rates are given in the
// form's unit (steps/ms/s on the 3601 and 3602) rather than the shared code's steps/s².
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "core/module_shape.hpp"

namespace stepmod::web {

// {"<code>": {"id", "condition", "fix"}} for every item module `type` numbers, and for each
// list's own code (number 0: the list's general fix), so the page can look any code up.
nlohmann::json reason_table(ModuleType type);
// The /reasons page: one row per item with its anchor (the item id, e.g. "3601-CE-05").
std::string reasons_page(ModuleType type);
// `text` with "accel A or decel D steps/s2" given as A / `accel_word_unit` in steps/ms/s when the
// module's form takes steps/ms/s (accel_word_unit 1000); unchanged otherwise.
std::string in_form_units(const std::string& text, std::int64_t accel_word_unit);

}  // namespace stepmod::web

#pragma once
// A small JSON Schema (draft 2020-12) checker for the schemas the project ships
// (docs/status.schema.json): enough of the keywords to pin a document's shape, and an error for
// any keyword it does not know, so a schema can never rely on something left unchecked.
// Keywords: $ref ("#/$defs/NAME"), type, enum, const, properties, required,
// additionalProperties (false), items, minItems, maxItems, minimum, oneOf, allOf, if/then;
// annotations ($schema, $id, $defs, title, description) are skipped.
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace stepmod::testing {

// Every way `doc` departs from `schema` ("axes[0].speed: not a number"); empty when it conforms.
// `schema` is the whole schema file (its $defs are looked up from the root).
std::vector<std::string> schema_violations(const nlohmann::json& schema, const nlohmann::json& doc);

// Every member a conforming document can have, as paths: "health.flags", "axes[].unit"
// (documentation tables list the same).
std::vector<std::string> schema_member_paths(const nlohmann::json& schema);

}  // namespace stepmod::testing

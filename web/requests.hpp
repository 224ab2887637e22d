#pragma once
// A WebSocket message from a page, taken apart defensively: whatever bytes arrive (binary, invalid
// UTF-8, not JSON, not an object, no string "op"), the answer is an error reply, never an
// exception; and no reply can make the JSON writer throw (invalid UTF-8 in a string from the
// image or an error message is written as U+FFFD).
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace stepmod::web {

class Commander;

// The request in `msg`, or an error reply ({"type": "reply", "ok": false, "message"}) in `error`.
bool parse_request(std::string_view msg, bool text, nlohmann::json& req, nlohmann::json& error);
// `j` as JSON text; never throws for bad UTF-8 in its strings (replaced by U+FFFD).
std::string safe_dump(const nlohmann::json& j);
// The reply text for message `msg` of connection `conn` (empty: none, as for a keep-alive).
std::string answer(Commander& commander, std::uintptr_t conn, std::string_view msg, bool text);

}  // namespace stepmod::web

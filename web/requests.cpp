#include "web/requests.hpp"

#include "web/commander.hpp"
#include "web/ws_frame.hpp"

namespace stepmod::web {
namespace {

nlohmann::json bad(const std::string& op, const std::string& why) {
  return {{"type", "reply"}, {"op", op}, {"ok", false}, {"message", "bad request: " + why}};
}

}  // namespace

bool parse_request(std::string_view msg, bool text, nlohmann::json& req, nlohmann::json& error) {
  if (!text) {
    error = bad("", "binary messages are not taken: send JSON text");
  } else if (!valid_utf8(msg)) {
    error = bad("", "the message is not valid UTF-8");
  } else {
    req = nlohmann::json::parse(msg, nullptr, /*allow_exceptions=*/false);
    if (req.is_discarded()) {
      error = bad("", "the message is not JSON");
    } else if (!req.is_object() || !req.contains("op") || !req["op"].is_string()) {
      error = bad("", "a request is a JSON object with a string \"op\"");
    } else {
      return true;
    }
  }
  return false;
}

std::string safe_dump(const nlohmann::json& j) {
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::string answer(Commander& commander, std::uintptr_t conn, std::string_view msg, bool text) {
  nlohmann::json req;
  nlohmann::json reply;
  if (!parse_request(msg, text, req, reply)) return safe_dump(reply);
  try {
    reply = commander.handle(req, conn);
  } catch (const std::exception& e) {  // a field of the wrong type, say: an answer, no crash
    reply = bad(req["op"].get<std::string>(), e.what());
  }
  return reply.is_null() ? std::string() : safe_dump(reply);
}

}  // namespace stepmod::web

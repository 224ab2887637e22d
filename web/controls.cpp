#include "web/controls.hpp"

#include <optional>
#include <stdexcept>
#include <string>

#include "web/module_views.hpp"
#include "web/path_request.hpp"

namespace stepmod::web {

std::int64_t request_int(const nlohmann::json& req, const char* name, std::int64_t lo,
                         std::int64_t hi) {
  if (!req.contains(name) || !req[name].is_number_integer()) {
    throw std::invalid_argument(std::string("missing integer field '") + name + "'");
  }
  const auto v = req[name].get<std::int64_t>();
  if (v < lo || v > hi) {
    throw std::invalid_argument(std::string(name) + " " + std::to_string(v) + " is outside " +
                                std::to_string(lo) + ".." + std::to_string(hi));
  }
  return v;
}

namespace {

bool cw_of(const nlohmann::json& req) {
  const std::string d = req.value("dir", "");
  if (d != "cw" && d != "ccw") throw std::invalid_argument("dir must be \"cw\" or \"ccw\"");
  return d == "cw";
}

}  // namespace

std::uint32_t Controls::config_bits(const nlohmann::json& req) const {
  return static_cast<std::uint32_t>(request_int(req, "msw", 0, 0xFFFF)) << 16 |
         static_cast<std::uint32_t>(request_int(req, "lsw", 0, 0xFFFF));
}

plc::Outcome Controls::run(const nlohmann::json& req) {
  const std::string cmd = req.value("cmd", "");
  const auto u = static_cast<unsigned>(request_int(req, "unit", 0, units() - 1));
  if (cmd == "move") {
    return move(
        u, req.value("absolute", false),
        static_cast<std::int32_t>(request_int(req, "target", -2'000'000'000, 2'000'000'000)),
        profile_of(req));
  }
  if (cmd == "jog_press") return jog_press(u, cw_of(req), profile_of(req));
  if (cmd == "jog_release") return jog_release(u);
  if (cmd == "home") return home(u, cw_of(req), profile_of(req));
  if (cmd == "hold") return hold(u);
  if (cmd == "resume") return resume(u);
  if (cmd == "stop") return stop(u);
  if (cmd == "reset") return reset(u);
  if (cmd == "preset") {
    return preset(
        u, static_cast<std::int32_t>(request_int(req, "position", -2'000'000'000, 2'000'000'000)));
  }
  if (cmd == "configure") {
    // The module checks the timeout's range (3602-CFG); a word it has not is refused here.
    const std::int64_t timeout =
        req.contains("homing_timeout") ? request_int(req, "homing_timeout", 0, 32767) : 0;
    if (timeout != 0 && !has_homing_timeout()) {
      throw std::invalid_argument("this module has no homing timeout: homing_timeout must be 0");
    }
    return configure(u, config_bits(req),
                     static_cast<std::int32_t>(request_int(req, "start_speed", 0, 2'000'000'000)),
                     static_cast<std::int16_t>(timeout));
  }
  if (std::optional<plc::Outcome> o = module_command(cmd, u, req)) return *o;
  throw std::invalid_argument("unknown command '" + cmd + "'");
}

std::unique_ptr<Controls> make_controls(plc::Port& port) {
  return view_of(port.type()).make_controls(port);
}

}  // namespace stepmod::web

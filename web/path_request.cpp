#include "web/path_request.hpp"

#include <cstdint>
#include <stdexcept>
#include <string>

#include "web/controls.hpp"

namespace stepmod::web {
namespace {
using Method = plc::PathMove3602::Method;

// Points and the radius travel as two 16-bit words each (3602 manual ch. 9): any int32.
std::int32_t point(const nlohmann::json& req, const char* name) {
  return static_cast<std::int32_t>(request_int(req, name, INT32_MIN, INT32_MAX));
}

Method circular(const nlohmann::json& req, Method cw, Method ccw) {
  const std::string s = req.contains("sense") && req["sense"].is_string() ? req["sense"] : "";
  if (s != "cw" && s != "ccw") throw std::invalid_argument("sense must be \"cw\" or \"ccw\"");
  return s == "cw" ? cw : ccw;
}
}  // namespace

bool request_bool(const nlohmann::json& req, const char* name) {
  if (!req.contains(name) || !req[name].is_boolean()) {
    throw std::invalid_argument(std::string("missing boolean field '") + name + "'");
  }
  return req[name].get<bool>();
}

plc::Profile profile_of(const nlohmann::json& req) {
  plc::Profile p;
  p.speed = static_cast<std::int32_t>(request_int(req, "speed", 0, 2'000'000'000));
  p.accel = static_cast<std::int32_t>(request_int(req, "accel", 0, 1'000'000));
  p.decel = static_cast<std::int32_t>(request_int(req, "decel", 0, 1'000'000));
  p.type = static_cast<plc::AccelType>(request_int(req, "profile", 0, 2));
  return p;
}

plc::PathMove3602 path_request(const nlohmann::json& req) {
  const std::string method =
      req.contains("method") && req["method"].is_string() ? req["method"] : "";
  plc::PathMove3602 m;
  if (method == "line") {
    m.method = Method::kLinear;
  } else if (method == "centre") {
    m.method = circular(req, Method::kCentreCw, Method::kCentreCcw);
    m.point_x = point(req, "point_x");
    m.point_y = point(req, "point_y");
  } else if (method == "radius") {
    m.method = circular(req, Method::kRadiusCw, Method::kRadiusCcw);
    m.radius = point(req, "radius");
  } else if (method == "via") {
    m.method = Method::kViaPoint;
    m.point_x = point(req, "point_x");
    m.point_y = point(req, "point_y");
  } else {
    throw std::invalid_argument("method must be \"line\", \"centre\", \"radius\" or \"via\"");
  }
  m.absolute = request_bool(req, "absolute");
  m.end_x = point(req, "end_x");
  m.end_y = point(req, "end_y");
  m.profile = profile_of(req);
  return m;
}

}  // namespace stepmod::web

#pragma once
// A 3602 interpolated move as the page asks for it ({"cmd": "path", "method": "line" | "centre" |
// "radius" | "via", "sense": "cw" | "ccw", "absolute", "end_x", "end_y", "point_x", "point_y",
// "radius", and the vector profile}), checked field by field before anything is written: the
// move stepmodctl's `path` sends (tools/ctl_path_3602.cpp), through the same plc/interp_3602.
#include <nlohmann/json.hpp>

#include "module_types/m3602/plc_interp_3602.hpp"

namespace stepmod::web {

// The move; std::invalid_argument naming the field for a missing, mistyped or unknown one.
plc::PathMove3602 path_request(const nlohmann::json& req);
// The vector or axis profile of a request ("speed", "accel", "decel", "profile"), each in range.
plc::Profile profile_of(const nlohmann::json& req);
// The boolean field `name` (std::invalid_argument when missing or not a boolean).
bool request_bool(const nlohmann::json& req, const char* name);

}  // namespace stepmod::web

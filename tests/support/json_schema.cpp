#include "tests/support/json_schema.hpp"

#include <algorithm>
#include <set>

namespace stepmod::testing {

namespace {

using nlohmann::json;

class Checker {
 public:
  explicit Checker(const json& root) : root_(root) {}
  std::vector<std::string> errors;

  void check(const json& s, const json& d, const std::string& at) {
    for (const auto& [key, value] : s.items()) {
      if (!keyword(key, value, s, d, at))
        errors.push_back(at + ": schema keyword '" + key + "' unknown");
    }
  }

  const json& resolve(const json& s) const {
    if (!s.contains("$ref")) return s;
    const std::string ref = s["$ref"];
    const std::string prefix = "#/$defs/";
    return root_.at("$defs").at(ref.substr(prefix.size()));
  }

 private:
  const json& root_;

  bool passes(const json& s, const json& d) const {
    Checker c(root_);
    c.check(s, d, "");
    return c.errors.empty();
  }

  // Exactly one alternative must match; when none does, the nearest one's violations say why.
  void one_of(const json& alternatives, const json& d, const std::string& at) {
    std::vector<std::string> nearest;
    std::size_t matches = 0;
    for (const json& alt : alternatives) {
      Checker c(root_);
      c.check(alt, d, at);
      if (c.errors.empty()) ++matches;
      if (nearest.empty() || c.errors.size() < nearest.size()) nearest = c.errors;
    }
    if (matches == 0) errors.insert(errors.end(), nearest.begin(), nearest.end());
    if (matches > 1) fail(at, "matches " + std::to_string(matches) + " alternatives of oneOf");
  }

  void fail(const std::string& at, const std::string& what) {
    errors.push_back((at.empty() ? "(document)" : at) + ": " + what);
  }

  static bool has_type(const std::string& t, const json& d) {
    if (t == "object") return d.is_object();
    if (t == "array") return d.is_array();
    if (t == "string") return d.is_string();
    if (t == "integer") return d.is_number_integer();
    if (t == "number") return d.is_number();
    if (t == "boolean") return d.is_boolean();
    return t == "null" && d.is_null();
  }

  void check_object(const json& s, const json& d, const std::string& at) {
    const json& props = s.contains("properties") ? s["properties"] : json::object();
    for (const auto& [name, sub] : props.items()) {
      if (d.contains(name)) check(sub, d[name], at.empty() ? name : at + "." + name);
    }
    const bool closed = s.contains("additionalProperties") && s["additionalProperties"] == false;
    for (const auto& [name, value] : d.items()) {
      if (closed && !props.contains(name)) fail(at, "member '" + name + "' is not in the schema");
    }
  }

  bool keyword(const std::string& k, const json& v, const json& s, const json& d,
               const std::string& at) {
    if (k == "$schema" || k == "$id" || k == "$defs" || k == "title" || k == "description" ||
        k == "then" || k == "additionalProperties") {
      return true;  // annotations; `then` goes with `if`, additionalProperties with properties
    }
    if (k == "$ref") {
      check(resolve(s), d, at);
    } else if (k == "type") {
      if (!has_type(v, d)) fail(at, "not of type " + v.get<std::string>() + ": " + d.dump());
    } else if (k == "const") {
      if (d != v) fail(at, d.dump() + " is not " + v.dump());
    } else if (k == "enum") {
      if (std::find(v.begin(), v.end(), d) == v.end())
        fail(at, d.dump() + " not one of " + v.dump());
    } else if (k == "properties") {
      if (d.is_object()) check_object(s, d, at);
    } else if (k == "required") {
      for (const auto& name : v) {
        if (d.is_object() && !d.contains(name))
          fail(at, "member '" + name.get<std::string>() + "' missing");
      }
    } else if (k == "items") {
      for (std::size_t i = 0; d.is_array() && i < d.size(); ++i) {
        check(v, d[i], at + "[" + std::to_string(i) + "]");
      }
    } else if (k == "minItems" || k == "maxItems") {
      const bool low = d.is_array() && d.size() < v.get<std::size_t>();
      const bool high = d.is_array() && d.size() > v.get<std::size_t>();
      if (k == "minItems" ? low : high)
        fail(at, std::to_string(d.size()) + " items, " + k + " " + v.dump());
    } else if (k == "minimum") {
      if (d.is_number() && d.get<double>() < v.get<double>())
        fail(at, d.dump() + " below " + v.dump());
    } else if (k == "oneOf") {
      one_of(v, d, at);
    } else if (k == "allOf") {
      for (const json& sub : v) check(sub, d, at);
    } else if (k == "if") {
      if (passes(v, d) && s.contains("then")) check(s["then"], d, at);
    } else {
      return false;
    }
    return true;
  }
};

void collect_paths(const Checker& c, const nlohmann::json& s, const std::string& at,
                   std::set<std::string>& out) {
  const nlohmann::json& r = c.resolve(s);
  for (const char* alt : {"oneOf", "allOf"}) {
    if (r.contains(alt)) {
      for (const auto& sub : r[alt]) collect_paths(c, sub, at, out);
    }
  }
  if (r.contains("items")) collect_paths(c, r["items"], at + "[]", out);
  if (!r.contains("properties")) return;
  for (const auto& [name, sub] : r["properties"].items()) {
    const std::string path = at.empty() ? name : at + "." + name;
    out.insert(path);
    collect_paths(c, sub, path, out);
  }
}

}  // namespace

std::vector<std::string> schema_violations(const nlohmann::json& schema,
                                           const nlohmann::json& doc) {
  Checker c(schema);
  c.check(schema, doc, "");
  return c.errors;
}

std::vector<std::string> schema_member_paths(const nlohmann::json& schema) {
  std::set<std::string> paths;
  collect_paths(Checker(schema), schema, "", paths);
  return {paths.begin(), paths.end()};
}

}  // namespace stepmod::testing

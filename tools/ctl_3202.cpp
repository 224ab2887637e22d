#include "tools/ctl_3202.hpp"

#include <fstream>

namespace stepmod::tools::ctl {

namespace {

std::int32_t number(const std::string& s, const std::string& what) {
  std::string t = s;
  bool neg = false;
  if (!t.empty() && (t[0] == '-' || t[0] == '+')) {
    neg = t[0] == '-';
    t.erase(0, 1);
  }
  int base = 10;
  if (t.rfind("0x", 0) == 0 || t.rfind("0X", 0) == 0) {
    base = 16;
    t.erase(0, 2);
  } else if (t.rfind("16#", 0) == 0) {
    base = 16;
    t.erase(0, 3);
  }
  std::size_t used = 0;
  long long v = 0;
  try {
    v = std::stoll(t, &used, base);
  } catch (const std::exception&) {
    used = 0;
  }
  if (t.empty() || used != t.size() || v > INT32_MAX || -v < INT32_MIN) {
    throw BlendSyntaxError(what + ": '" + s + "' is not a 32-bit number");
  }
  return static_cast<std::int32_t>(neg ? -v : v);
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

// A comment starts with '#' at the start of the line or after a blank: 16#FF stays a number.
std::string strip_comment(const std::string& line) {
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] == '#' && (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t')) {
      return line.substr(0, i);
    }
  }
  return line;
}

}  // namespace

plc::AccelType parse_accel_type(const std::string& s) {
  if (s.empty() || s == "const" || s == "constant") return plc::AccelType::kConstant;
  if (s == "tri" || s == "triangular") return plc::AccelType::kTriangularS;
  if (s == "trap" || s == "trapezoidal") return plc::AccelType::kTrapezoidalS;
  throw BlendSyntaxError("acceleration type must be const, tri or trap, not '" + s + "'");
}

plc::BlendSegment parse_blend_segment(const std::string& s) {
  std::vector<std::string> f;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= s.size(); ++i) {
    if (i == s.size() || s[i] == ':') {
      f.push_back(s.substr(start, i - start));
      start = i + 1;
    }
  }
  if (f.size() < 3 || f.size() > 4) {
    throw BlendSyntaxError("segment '" + s + "': expected LENGTH:SPEED:ACCEL[:tri|trap]");
  }
  return {number(f[0], "LENGTH"), number(f[1], "SPEED"), number(f[2], "ACCEL"),
          parse_accel_type(f.size() == 4 ? f[3] : "")};
}

plc::BlendProfile read_blend_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw BlendSyntaxError(path + ": cannot be read");
  plc::BlendProfile b;
  bool have_final = false;
  std::string line;
  for (unsigned n = 1; std::getline(in, line); ++n) {
    line = trim(strip_comment(line));
    if (line.empty()) continue;
    const auto eq = line.find('=');
    const std::string where = path + ":" + std::to_string(n);
    if (eq == std::string::npos) throw BlendSyntaxError(where + ": expected key = value");
    const std::string key = trim(line.substr(0, eq));
    const std::string value = trim(line.substr(eq + 1));
    try {
      if (key == "segment") {
        b.segments.push_back(parse_blend_segment(value));
      } else if (key == "final_decel") {
        b.final_decel = number(value, "final_decel");
        have_final = true;
      } else if (key == "final_type") {
        b.final_type = parse_accel_type(value);
      } else {
        throw BlendSyntaxError("unknown key '" + key + "' (segment, final_decel, final_type)");
      }
    } catch (const BlendSyntaxError& e) {
      throw BlendSyntaxError(where + ": " + e.what());
    }
  }
  if (b.segments.empty()) throw BlendSyntaxError(path + ": no segment");
  if (!have_final) throw BlendSyntaxError(path + ": no final_decel");
  return b;
}

}  // namespace stepmod::tools::ctl

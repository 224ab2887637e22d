#include "tools/ctl_blend.hpp"

#include <cstdint>
#include <fstream>

namespace stepmod::tools::ctl {

namespace {

std::int32_t number(const std::string& s, const std::string& what) {
  return static_cast<std::int32_t>(
      parse_in_range(s, what, INT32_MIN, INT32_MAX, "a 32-bit number"));
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
    throw UsageError("segment '" + s + "': expected LENGTH:SPEED:ACCEL[:tri|trap]");
  }
  return {number(f[0], "LENGTH"), number(f[1], "SPEED"), number(f[2], "ACCEL"),
          parse_accel_type(f.size() == 4 ? f[3] : "")};
}

plc::BlendProfile read_blend_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw UsageError(path + ": cannot be read");
  plc::BlendProfile b;
  bool have_final = false;
  std::string line;
  for (unsigned n = 1; std::getline(in, line); ++n) {
    line = trim(strip_comment(line));
    if (line.empty()) continue;
    const auto eq = line.find('=');
    const std::string where = path + ":" + std::to_string(n);
    if (eq == std::string::npos) throw UsageError(where + ": expected key = value");
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
        throw UsageError("unknown key '" + key + "' (segment, final_decel, final_type)");
      }
    } catch (const UsageError& e) {
      throw UsageError(where + ": " + e.what());
    }
  }
  if (b.segments.empty()) throw UsageError(path + ": no segment");
  if (!have_final) throw UsageError(path + ": no final_decel");
  return b;
}

plc::BlendProfile blend_from_options(const std::string& file,
                                     const std::vector<std::string>& segments,
                                     const std::string& final_decel,
                                     const std::string& final_type) {
  if (!file.empty()) {
    if (!segments.empty() || !final_decel.empty() || !final_type.empty()) {
      throw UsageError("blend program: --file or --segment/--final-decel/--final-type, not both");
    }
    return read_blend_file(file);
  }
  if (segments.empty() || final_decel.empty()) {
    throw UsageError("blend program: --segment (2..16 times) and --final-decel, or --file");
  }
  plc::BlendProfile b;
  for (const std::string& s : segments) {
    try {
      b.segments.push_back(parse_blend_segment(s));
    } catch (const UsageError& e) {
      throw UsageError(std::string("--segment: ") + e.what());
    }
  }
  b.final_decel = number(final_decel, "--final-decel");
  b.final_type = parse_accel_type(final_type);
  return b;
}

}  // namespace stepmod::tools::ctl

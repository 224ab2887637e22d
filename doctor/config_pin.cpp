// pin_in_config (doctor/isolate.hpp): `[rt] cpu = N` set in a module's config file as text, so
// that the user's comments and layout stay as they were; every line it adds or changes carries
// kPinMark, and only those lines are removed again.
#include <sstream>
#include <vector>

#include "doctor/isolate.hpp"

namespace stepmod::doctor {

namespace {

constexpr const char* kPinMark = "  # set by stepmodctl isolate";

std::string trim_left(const std::string& s) {
  const auto p = s.find_first_not_of(" \t");
  return p == std::string::npos ? "" : s.substr(p);
}

bool is_table_header(const std::string& line) {
  return trim_left(line).rfind('[', 0) == 0;
}

bool is_rt_header(const std::string& line) {
  const std::string t = trim_left(line);
  return t.rfind("[rt]", 0) == 0;
}

bool is_cpu_key(const std::string& line) {
  const std::string t = trim_left(line);
  if (t.rfind("cpu", 0) != 0) return false;
  const auto rest = trim_left(t.substr(3));
  return !rest.empty() && rest.front() == '=';
}

bool marked(const std::string& line) {
  return line.find(kPinMark) != std::string::npos;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

std::string text_of(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

std::vector<std::string> unpinned(std::vector<std::string> lines) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (!marked(lines[i])) {
      out.push_back(lines[i]);
      continue;
    }
    // The user's own cpu line, commented out by the pin: restored as it was.
    if (lines[i].rfind("# ", 0) == 0 && is_cpu_key(lines[i].substr(2))) {
      out.push_back(lines[i].substr(2, lines[i].find(kPinMark) - 2));
      continue;
    }
    // A marked [rt] header was added with its cpu line: it goes too; a blank line before it also.
    if (is_rt_header(lines[i]) && !out.empty() && out.back().empty()) out.pop_back();
  }
  return out;
}

}  // namespace

std::string pin_in_config(const std::string& toml, int cpu) {
  std::vector<std::string> lines = unpinned(lines_of(toml));
  if (cpu < 0) return text_of(lines);
  const std::string pin = "cpu = " + std::to_string(cpu) + kPinMark;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (!is_rt_header(lines[i])) continue;
    std::size_t j = i + 1;
    for (; j < lines.size() && !is_table_header(lines[j]); ++j) {
      if (is_cpu_key(lines[j])) {
        lines[j] = "# " + lines[j] + kPinMark;  // the user's own value, kept as a comment
        lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(j) + 1, pin);
        return text_of(lines);
      }
    }
    lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(i) + 1, pin);
    return text_of(lines);
  }
  lines.push_back("");
  lines.push_back(std::string("[rt]") + kPinMark);
  lines.push_back(pin);
  return text_of(lines);
}

}  // namespace stepmod::doctor

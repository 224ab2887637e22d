// Reading what docs/interface.md, stepmod.toml(5) and the examples state about each key: plain
// text matching on their fixed shapes (a Markdown table row per key, a man page .TP entry per
// key), normalised to ASCII so that one set of patterns reads both.
#include "tests/tools/config_doc_statements.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <utility>

#include "config/config_keys.hpp"

namespace stepmod::tools {
namespace {

void replace_all(std::string& s, const std::string& from, const std::string& to) {
  for (auto at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) {
    s.replace(at, from.size(), to);
  }
}

// Superscript digits as an exponent: "10¹²" -> "10^12".
std::string caret_exponents(const std::string& s) {
  static const std::string kDigits[] = {"\u2070", "\u00b9", "\u00b2", "\u00b3", "\u2074",
                                        "\u2075", "\u2076", "\u2077", "\u2078", "\u2079"};
  std::string out;
  bool in_exponent = false;
  for (std::size_t i = 0; i < s.size();) {
    int digit = -1;
    for (int d = 0; d < 10 && digit < 0; ++d) {
      if (s.compare(i, kDigits[d].size(), kDigits[d]) == 0) digit = d;
    }
    if (digit < 0) {
      out += s[i++];
      in_exponent = false;
      continue;
    }
    if (!in_exponent) out += '^';
    out += static_cast<char>('0' + digit);
    i += kDigits[digit].size();
    in_exponent = true;
  }
  return out;
}

// ASCII: minus, ranges ("..", "+-", ">="), no Markdown code spans, no roff escapes, one line.
std::string normalise(std::string s) {
  const std::pair<const char*, const char*> map[] = {
      {"\u2212", "-"},  {"\u2026", ".."}, {"\u2013", ".."}, {"\u00b1", "+-"},
      {"\u2265", ">="}, {"`", ""},        {"\\-", "-"},     {"\\(dq", "\""},
      {"\\fB", ""},     {"\\fR", ""},     {"\\fI", ""},     {"\n", " "}};
  for (const auto& [from, to] : map) replace_all(s, from, to);
  return caret_exponents(s);
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  const auto e = s.find_last_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

// "1000", "-1", "10^12", "-10^12".
std::int64_t number(const std::string& token) {
  if (!token.empty() && token[0] == '-') return -number(token.substr(1));
  const auto caret = token.find('^');
  if (caret == std::string::npos) return std::stoll(token);
  std::int64_t v = 1;
  for (int i = std::stoi(token.substr(caret + 1)); i > 0; --i)
    v *= std::stoll(token.substr(0, caret));
  return v;
}

std::vector<std::string> cells(const std::string& row) {
  std::vector<std::string> out;
  std::stringstream ss(row);
  std::string cell;
  while (std::getline(ss, cell, '|')) out.push_back(trim(cell));
  if (!out.empty() && out.front().empty()) out.erase(out.begin());
  return out;
}

}  // namespace

std::string read_source_text(const std::string& relative) {
  std::ifstream in(std::string(STEPMOD_SOURCE_DIR) + "/" + relative, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::map<std::string, DocStatement> interface_md_statements() {
  const std::string text = read_source_text("docs/interface.md");
  const auto from = text.find("<!-- config-keys:begin");
  const auto to = text.find("<!-- config-keys:end");
  std::map<std::string, DocStatement> out;
  if (from == std::string::npos || to == std::string::npos) return out;
  std::stringstream rows(text.substr(from, to - from));
  for (std::string row; std::getline(rows, row);) {
    const std::vector<std::string> c = cells(row);
    if (c.size() != 4 || c[0].size() < 3 || c[0].front() != '`') continue;
    out[c[0].substr(1, c[0].size() - 2)] = {normalise(c[1]), normalise(c[2]), "", c[3],
                                            normalise(row)};
  }
  return out;
}

std::map<std::string, DocStatement> man_page_statements() {
  const std::string text = read_source_text("packaging/man/stepmod.toml.5");
  const auto keys = text.find("\n.SH KEYS");
  const auto end = text.find("\n.SH", keys + 1);
  std::map<std::string, DocStatement> out;
  if (keys == std::string::npos) return out;
  const std::regex entry_head(R"(\n\.B ([a-z_]+(?:\.[a-z_]+)+)\n)");
  const auto first = text.begin() + static_cast<std::ptrdiff_t>(keys);
  const auto last = text.begin() + static_cast<std::ptrdiff_t>(end);
  for (std::sregex_iterator it(first, last, entry_head), none; it != none; ++it) {
    const auto at = keys + static_cast<std::size_t>(it->position(0) + it->length(0));
    std::size_t stop = std::min({text.find("\n.TP", at), text.find("\n.SS", at), end});
    const std::string entry = normalise(text.substr(at, stop - at));
    // Its subsection's preamble: from the .SS line to the subsection's first entry.
    const auto ss = text.rfind("\n.SS", at);
    const auto ss_body = text.find('\n', ss + 1);
    const std::string preamble =
        normalise(text.substr(ss_body, text.find("\n.TP", ss_body) - ss_body));
    out[(*it)[1]] = {entry, entry, preamble, "", entry};
  }
  return out;
}

std::optional<Range> parse_range(const std::string& text) {
  const std::string num = R"((-?\d+(?:\^\d+)?))";
  const std::regex span(num + R"(\s*(?:\.\.|to)\s*)" + num);
  const std::regex plus_minus(R"(\+-\s*(\d+(?:\^\d+)?))");
  const std::regex at_least(R"((?:>=|at least)\s*(-?\d+))");
  std::smatch best;
  int kind = -1;
  const std::regex* patterns[] = {&span, &plus_minus, &at_least};
  for (int k = 0; k < 3; ++k) {
    std::smatch m;
    if (std::regex_search(text, m, *patterns[k]) &&
        (kind < 0 || m.position(0) < best.position(0))) {
      best = m;
      kind = k;
    }
  }
  if (kind == 0) return Range{number(best[1]), number(best[2])};
  if (kind == 1) return Range{-number(best[1]), number(best[1])};
  if (kind == 2) return Range{number(best[1]), kUnbounded};
  return std::nullopt;
}

std::optional<std::string> parse_default(const std::string& text, bool man) {
  const std::string value = R"(("[^"]*"|\[\]|-?\d+(?:\.\d+)?|true|false))";
  std::smatch m;
  if (man) {
    if (text.find("Required.") != std::string::npos) return "required";
    if (std::regex_search(text, m, std::regex(R"(Default:?\s+)" + value))) return m[1];
    return std::nullopt;
  }
  if (text.rfind("(required)", 0) == 0) return "required";
  if (std::regex_search(text, m, std::regex("^" + value))) return m[1];
  return std::nullopt;
}

std::set<std::string> quoted_strings(const std::string& text) {
  std::set<std::string> out;
  const std::regex quoted(R"re("([^"]*)")re");
  for (std::sregex_iterator it(text.begin(), text.end(), quoted), none; it != none; ++it) {
    out.insert((*it)[1]);
  }
  return out;
}

std::vector<ExampleDefault> example_defaults() {
  std::vector<std::filesystem::path> files;
  for (const auto& e :
       std::filesystem::directory_iterator(std::string(STEPMOD_SOURCE_DIR) + "/examples")) {
    if (e.path().extension() == ".toml") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  const std::regex header(R"(^\[\[?([a-z.]+)\]\]?)");
  const std::regex assignment(R"re(([a-z_]+) = ("[^"]*"|\[[^\]]*\]|[-0-9.]+|true|false))re");
  std::vector<ExampleDefault> out;
  for (const auto& path : files) {
    const std::string name = "examples/" + path.filename().string();
    std::stringstream lines(read_source_text(name));
    std::string table;
    int n = 0;
    for (std::string line; std::getline(lines, line);) {
      ++n;
      std::smatch m;
      if (std::regex_search(line, m, header)) table = m[1];
      if (line.rfind('#', 0) != 0 || line.find("default") == std::string::npos) continue;
      std::vector<std::smatch> found;
      for (std::sregex_iterator it(line.begin(), line.end(), assignment), none; it != none; ++it) {
        found.push_back(*it);
      }
      if (found.size() == 1) out.push_back({name, n, table, found[0][1], found[0][2]});
    }
  }
  return out;
}

}  // namespace stepmod::tools

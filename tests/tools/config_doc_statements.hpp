#pragma once
// What the documents state about each configuration key, read from their text: the rows of
// docs/interface.md's key table, the entries of the stepmod.toml(5) man page's KEYS section and
// the examples' commented-out defaults. tests/tools/config_defaults_doc_test.cpp compares them
// with the key table (config/config_keys.hpp).
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace stepmod::tools {

std::string read_source_text(const std::string& relative);  // relative to the source tree

// One document's statement about one key, normalised to ASCII ("-" for U+2212, no Markdown
// backticks, no roff escapes).
struct DocStatement {
  std::string default_text;  // interface.md: the default cell; man page: the entry
  std::string range_text;    // interface.md: the range cell; man page: the entry
  std::string
      fallback_range;   // man page: its subsection's preamble ("Line offsets ..., 0 to 4095")
  std::string meaning;  // interface.md: the meaning cell, as written (Markdown)
  std::string whole;    // the whole row or entry
};

// "module.scan_us" -> statement.
std::map<std::string, DocStatement> interface_md_statements();
std::map<std::string, DocStatement> man_page_statements();

struct Range {
  std::int64_t min = 0;
  std::int64_t max = 0;
};
// The first range `text` states: "20 … 1000000", "1–64", "-1 to 1023", "±10¹²", "-10^12 to
// 10^12", "≥ 1", "at least 1" ("≥"/"at least": no upper bound, kUnbounded).
std::optional<Range> parse_range(const std::string& text);

// The default `text` states: "(required)" / "Required." -> "required"; a number, a quoted
// string, "[]", true/false as written; nullopt when it states no value (not wired, never, ...).
// `man`: the man page's "Default X" form.
std::optional<std::string> parse_default(const std::string& text, bool man);

// The quoted strings in `text`: {"sim", "gpiod"}.
std::set<std::string> quoted_strings(const std::string& text);

// A commented-out `key = value` that an example file says is the default
// (`# late_limit_us = 200000   # the default ...`).
struct ExampleDefault {
  std::string file;  // examples/3601-sim.toml
  int line = 0;
  std::string table;  // the table it stands in: "rt", "axis", "axis.sim"
  std::string key;
  std::string value;  // as written
};
std::vector<ExampleDefault> example_defaults();

}  // namespace stepmod::tools

// The defaults, ranges, off values and choices that docs/interface.md's key table, the
// stepmod.toml(5) man page and the examples' commented-out defaults state, against the key table
// the parser takes them from (config/config_keys.hpp): change a default or a range there without
// the documents, and each failure names the document, the key, what it states and what the table
// has.
#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>

#include "tests/tools/config_doc_statements.hpp"
#include "config/config_keys.hpp"

namespace stepmod::tools {
namespace {

bool has_numeric_range(const ConfigKey& k) {
  return k.type == KeyType::kInt || k.type == KeyType::kNumber || k.type == KeyType::kLine ||
         (k.type == KeyType::kText && k.max > 0);
}

// The default as the documents write it ("200000", "\"sim\"", "[]", "false"; "required").
std::optional<std::string> expected_default(const ConfigKey& k) {
  if (k.absent == Absent::kRequired) return "required";
  if (k.absent == Absent::kUnset) return std::nullopt;
  switch (k.type) {
    case KeyType::kInt:
      return std::to_string(k.def);
    case KeyType::kBool:
      return k.def != 0 ? "true" : "false";
    case KeyType::kText:
    case KeyType::kChoice:
      return std::string(1, '"').append(k.text).append(1, '"');
    default:
      return std::string(k.text);  // kList; kNumber: compared as a number
  }
}

std::string shown(const std::optional<std::string>& v) {
  return v ? *v : "no value";
}

// What `doc` (the document `where`) states about `k` that the table does not; "" if nothing.
std::string disagreement(const ConfigKey& k, const DocStatement& doc, const std::string& where,
                         bool man) {
  const std::string name = config_key_name(k);
  std::string out;
  const auto say = [&](const std::string& what) {
    out += "  " + name + ": " + where + " " + what + "\n";
  };
  const auto stated = parse_default(doc.default_text, man);
  const auto want = expected_default(k);
  const bool same_number = k.type == KeyType::kNumber && stated && want &&
                           std::stod(*stated) == static_cast<double>(k.def);
  if (k.type == KeyType::kNumber ? !same_number : stated != want) {
    say("states default " + shown(stated) + ", the key table " +
        (k.type == KeyType::kNumber ? std::to_string(k.def) : shown(want)));
  }
  if (!man && k.absent == Absent::kUnset && doc.default_text.rfind(k.text, 0) != 0) {
    say("states default '" + doc.default_text + "', the key table '" + std::string(k.text) + "'");
  }
  if (has_numeric_range(k)) {
    auto range = parse_range(doc.range_text);
    if (!range && man) range = parse_range(doc.fallback_range);
    const std::string want_range =
        std::to_string(k.min) + " .. " + (k.max == kUnbounded ? "" : std::to_string(k.max));
    if (!range || range->min != k.min || range->max != k.max) {
      say("states range " +
          (range ? std::to_string(range->min) + " .. " +
                       (range->max == kUnbounded ? "" : std::to_string(range->max))
                 : "none") +
          ", the key table " + want_range);
    }
  }
  const std::string off = k.off ? std::to_string(*k.off) + " (off" : "";
  if (k.off && doc.whole.find(off) == std::string::npos) {
    say("does not state the off value: '" + off + "...' expected");
  }
  if (!k.off && doc.whole.find("(off") != std::string::npos) {
    say("states an off value; the key table has none");
  }
  return out;
}

// The key's choices stated in `text` (its quoted strings), against the table's.
std::string choice_disagreement(const ConfigKey& k, const std::string& text,
                                const std::string& where) {
  std::set<std::string> want;
  for (std::string_view c : k.choices) {
    if (!c.empty()) want.insert(std::string(c));
  }
  if (want.empty()) return "";
  const std::set<std::string> stated = quoted_strings(text);
  if (stated == want) return "";
  std::string list;
  for (const auto& c : stated) list.append(" \"").append(c).append(1, '"');
  return "  " + config_key_name(k) + ": " + where + " states the choices" + list +
         ", not exactly the key table's\n";
}

std::string check_all(const std::map<std::string, DocStatement>& docs, const std::string& where,
                      bool man) {
  std::string out;
  for (const ConfigKey& k : kConfigKeys) {
    if (k.type == KeyType::kTable) continue;
    const auto it = docs.find(config_key_name(k));
    if (it == docs.end()) continue;  // config_keys_doc_test.cpp reports a missing key
    out += disagreement(k, it->second, where, man);
    out += choice_disagreement(k, man ? it->second.whole : it->second.range_text, where);
  }
  return out;
}

TEST(ConfigDefaultsDoc, InterfaceMdStatesTheTablesDefaultsAndRanges) {
  const auto docs = interface_md_statements();
  ASSERT_FALSE(docs.empty()) << "docs/interface.md: no key table between the config-keys markers";
  const std::string problems = check_all(docs, "docs/interface.md", false);
  EXPECT_TRUE(problems.empty()) << "docs/interface.md section 2 disagrees with "
                                   "config/config_keys.hpp:\n"
                                << problems;
}

TEST(ConfigDefaultsDoc, ManPageStatesTheTablesDefaultsAndRanges) {
  const auto docs = man_page_statements();
  ASSERT_FALSE(docs.empty()) << "packaging/man/stepmod.toml.5: no KEYS section";
  const std::string problems = check_all(docs, "stepmod.toml(5)", true);
  EXPECT_TRUE(problems.empty()) << "packaging/man/stepmod.toml.5 disagrees with "
                                   "config/config_keys.hpp:\n"
                                << problems;
}

TEST(ConfigDefaultsDoc, InterfaceMdMeaningIsTheTablesDoc) {
  const auto docs = interface_md_statements();
  for (const ConfigKey& k : kConfigKeys) {
    const auto it = docs.find(config_key_name(k));
    if (k.type == KeyType::kTable || it == docs.end()) continue;
    EXPECT_EQ(it->second.meaning, k.doc)
        << config_key_name(k) << ": docs/interface.md's meaning cell and the row's doc text "
        << "(config/config_keys.hpp) differ";
  }
}

TEST(ConfigDefaultsDoc, ExamplesCommentedDefaultsAreTheTables) {
  const auto found = example_defaults();
  EXPECT_FALSE(found.empty()) << "no example states a default in a comment any more";
  for (const ExampleDefault& e : found) {
    const ConfigKey* k = find_config_key(e.table, e.key);
    if (k == nullptr) k = find_config_key("line", e.key);
    const std::string where = e.file + ":" + std::to_string(e.line) + ": " + e.key;
    if (k == nullptr) {
      ADD_FAILURE() << where << ": not a key of [" << e.table << "] (config/config_keys.hpp)";
      continue;
    }
    const auto want = expected_default(*k);
    EXPECT_EQ(e.value, shown(want)) << where << " = " << e.value
                                    << " is called the default; the key table's is " << shown(want);
  }
}

// A time key's name says its unit, which the parser converts by (ConfigKey::unit).
TEST(ConfigDefaultsDoc, TimeKeysNameTheirUnit) {
  const std::pair<const char*, Unit> suffixes[] = {
      {"_ns", Unit::kNs}, {"_us", Unit::kUs}, {"_ms", Unit::kMs}, {"_steps", Unit::kSteps}};
  for (const auto& rows :
       {std::span<const ConfigKey>(kConfigKeys), std::span<const ConfigKey>(kLineOptionKeys)}) {
    for (const ConfigKey& k : rows) {
      for (const auto& [suffix, unit] : suffixes) {
        const bool named = k.key.ends_with(suffix);
        if (named) {
          EXPECT_EQ(k.unit, unit) << config_key_name(k);
        }
        if (unit != Unit::kSteps && k.unit == unit) {
          EXPECT_TRUE(named) << config_key_name(k);
        }
      }
    }
  }
}

}  // namespace
}  // namespace stepmod::tools

// The value readers of the configuration parser: every default and range comes from the key's
// row (config/config_keys.hpp), so that the parser states none of its own.
#include "config/config_reader.hpp"

#include <cmath>

#include "config/config.hpp"

namespace stepmod::tools {

void ConfigReader::fail(const toml::source_region& where, const std::string& key,
                        const std::string& what) const {
  std::string loc = file_;
  if (where.begin.line > 0) loc += ":" + std::to_string(where.begin.line);
  throw ConfigError(loc + ": key '" + key + "': " + what);
}

toml::table ConfigReader::parse(std::string_view text) const {
  try {
    return toml::parse(text, file_);
  } catch (const toml::parse_error& e) {
    throw ConfigError(file_ + ":" + std::to_string(e.source().begin.line) +
                      ": TOML syntax error: " + std::string(e.description()));
  }
}

void ConfigReader::check_keys(const toml::table& t, const std::string& prefix,
                              std::string_view table) const {
  check_keys_in(t, prefix, config_keys_of(table));
}

void ConfigReader::check_keys(const toml::table& t, const std::string& prefix,
                              std::initializer_list<std::string_view> allowed) const {
  check_keys_in(t, prefix, std::vector<std::string_view>(allowed));
}

void ConfigReader::check_keys_in(const toml::table& t, const std::string& prefix,
                                 const std::vector<std::string_view>& allowed) const {
  for (auto&& [k, v] : t) {
    bool ok = false;
    for (std::string_view a : allowed) ok = ok || k.str() == a;
    if (!ok) {
      std::string list;
      for (std::string_view a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      fail(k.source(), join(prefix, k.str()), "unknown key (expected one of: " + list + ")");
    }
  }
}

const toml::table* ConfigReader::sub_table(const toml::table& t, const std::string& prefix,
                                           std::string_view key) const {
  const toml::node* n = t.get(key);
  if (n == nullptr) return nullptr;
  if (!n->is_table()) {
    fail(n->source(), join(prefix, key), "must be a table [" + join(prefix, key) + "]");
  }
  return n->as_table();
}

std::string ConfigReader::range_text(const ConfigKey& k) {
  if (k.max == kUnbounded) return "must be an integer >= " + std::to_string(k.min);
  return "must be an integer " + std::to_string(k.min) + ".." + std::to_string(k.max);
}

std::string ConfigReader::choices_text(const ConfigKey& k, std::string_view last) {
  std::size_t count = 0;
  while (count < k.choices.size() && !k.choices[count].empty()) ++count;
  std::string list;
  for (std::size_t i = 0; i < count; ++i) {
    if (i > 0) list.append(i + 1 == count ? last : std::string_view(", "));
    list.append(1, '"').append(k.choices[i]).append(1, '"');
  }
  return list;
}

std::optional<std::int64_t> ConfigReader::opt_int(const toml::table* t, const std::string& prefix,
                                                  const ConfigKey& k) const {
  if (t == nullptr) return std::nullopt;
  const toml::node* n = t->get(k.key);
  if (n == nullptr) return std::nullopt;
  const auto* v = n->as_integer();
  if (v == nullptr || v->get() < k.min || v->get() > k.max) {
    fail(n->source(), join(prefix, k.key), range_text(k));
  }
  return v->get();
}

double ConfigReader::get_number(const toml::table* t, const std::string& prefix,
                                const ConfigKey& k) const {
  const toml::node* n = t != nullptr ? t->get(k.key) : nullptr;
  if (n == nullptr) return static_cast<double>(k.def);
  std::optional<double> v;
  if (const auto* f = n->as_floating_point()) v = f->get();
  if (const auto* i = n->as_integer()) v = static_cast<double>(i->get());
  if (!v || !std::isfinite(*v) || *v < static_cast<double>(k.min) ||
      *v > static_cast<double>(k.max)) {
    fail(n->source(), join(prefix, k.key),
         "must be a finite number, " + std::to_string(k.min) + " .. " + std::to_string(k.max));
  }
  return *v;
}

bool ConfigReader::get_bool(const toml::table* t, const std::string& prefix,
                            const ConfigKey& k) const {
  const toml::node* n = t != nullptr ? t->get(k.key) : nullptr;
  if (n == nullptr) return k.def != 0;
  const auto* b = n->as_boolean();
  if (b == nullptr) fail(n->source(), join(prefix, k.key), "must be true or false");
  return b->get();
}

std::string ConfigReader::get_choice(const toml::table* t, const std::string& prefix,
                                     const ConfigKey& k) const {
  const toml::node* n = t != nullptr ? t->get(k.key) : nullptr;
  if (n == nullptr) return std::string(k.text);
  if (const auto* s = n->as_string()) {
    for (std::string_view c : k.choices) {
      if (!c.empty() && s->get() == c) return s->get();
    }
  }
  fail(n->source(), join(prefix, k.key), "must be one of " + choices_text(k));
}

std::vector<unsigned> ConfigReader::get_choice_list(const toml::table* t, const std::string& prefix,
                                                    const ConfigKey& k) const {
  const toml::node* n = t != nullptr ? t->get(k.key) : nullptr;
  if (n == nullptr) return {};
  const std::string what =
      "must be a list of " + choices_text(k) + " (default " + std::string(k.text) + ")";
  const toml::array* arr = n->as_array();
  if (arr == nullptr) fail(n->source(), join(prefix, k.key), what);
  std::vector<unsigned> picked;
  for (const toml::node& e : *arr) {
    const auto* s = e.as_string();
    const std::string v = s != nullptr ? s->get() : "";
    unsigned i = 0;
    while (i < k.choices.size() && (v.empty() || v != k.choices[i])) ++i;
    if (i == k.choices.size()) fail(e.source(), join(prefix, k.key), what);
    picked.push_back(i);
  }
  return picked;
}

}  // namespace stepmod::tools

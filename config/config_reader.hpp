#pragma once
// The configuration parser's value readers: one key of a TOML table, checked against its row of
// the key table (config/config_keys.hpp), which gives its default (a key left out, or a table
// left out: `t` null) and its range. A bad value is a ConfigError naming the file, the line, the
// key and what it must be.
#include <toml++/toml.h>

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/clock.hpp"
#include "config/config_keys.hpp"

namespace stepmod::tools {

class ConfigReader {
 public:
  explicit ConfigReader(std::string file) : file_(std::move(file)) {}

  const std::string& file() const { return file_; }

  // The whole file as TOML; a syntax error is a ConfigError with its line.
  toml::table parse(std::string_view text) const;

  [[noreturn]] void fail(const toml::source_region& where, const std::string& key,
                         const std::string& what) const;

  static std::string join(const std::string& prefix, std::string_view key) {
    return prefix.empty() ? std::string(key) : prefix + "." + std::string(key);
  }

  // `table` names the table in kConfigKeys ("axis.sim"); `prefix` is how the message names it
  // ("axis[1].sim").
  void check_keys(const toml::table& t, const std::string& prefix, std::string_view table) const;
  // A line table's options: their own short lists, per direction (docs/gpio-boards.md).
  void check_keys(const toml::table& t, const std::string& prefix,
                  std::initializer_list<std::string_view> allowed) const;

  // A [table] that may be absent (null: all defaults); anything else under that name is an error.
  const toml::table* sub_table(const toml::table& t, const std::string& prefix,
                               std::string_view key) const;

  // "must be an integer 20..1000000", "... >= 1": the range of `k`.
  static std::string range_text(const ConfigKey& k);
  // `"sim", "gpiod"` (`last` = ", ") or `"3601", "3602" or "3202"` (`last` = " or ").
  static std::string choices_text(const ConfigKey& k, std::string_view last = ", ");

  // The value of integer key `k` in `t` (null: absent), within its range; nullopt when absent.
  std::optional<std::int64_t> opt_int(const toml::table* t, const std::string& prefix,
                                      const ConfigKey& k) const;
  // The same, its default when absent.
  std::int64_t get_int(const toml::table* t, const std::string& prefix, const ConfigKey& k) const {
    return opt_int(t, prefix, k).value_or(k.def);
  }
  // A time key in nanoseconds (its unit: ConfigKey::unit).
  Nanos get_ns(const toml::table* t, const std::string& prefix, const ConfigKey& k) const {
    return get_int(t, prefix, k) * unit_ns(k.unit);
  }
  // A number key (a float or an integer, finite, within its range); its default when absent.
  double get_number(const toml::table* t, const std::string& prefix, const ConfigKey& k) const;
  bool get_bool(const toml::table* t, const std::string& prefix, const ConfigKey& k) const;
  // One of `k.choices`; its default when absent.
  std::string get_choice(const toml::table* t, const std::string& prefix, const ConfigKey& k) const;
  // A list of `k.choices` (absent: none); each entry's index in `k.choices`.
  std::vector<unsigned> get_choice_list(const toml::table* t, const std::string& prefix,
                                        const ConfigKey& k) const;

 private:
  void check_keys_in(const toml::table& t, const std::string& prefix,
                     const std::vector<std::string_view>& allowed) const;

  std::string file_;
};

}  // namespace stepmod::tools

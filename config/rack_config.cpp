// The rack file of docs/interface.md section 7: [rack] modules and the rack's [rt]; every module
// file read as a daemon of its own would read it (section 2), then given the rack's [rt].
#include "config/rack_config.hpp"

#include <toml++/toml.h>

#include <filesystem>

#include "config/config_reader.hpp"
#include "config/rt_section.hpp"

namespace stepmod::tools {
namespace {

class RackParser : ConfigReader {
 public:
  explicit RackParser(std::string file) : ConfigReader(std::move(file)) {}

  RackConfig run(const toml::table& root) const {
    if (const toml::node* m = root.get("module")) {
      fail(m->source(), "module",
           "a rack file names its modules in rack.modules and has no [module] table of its own "
           "(docs/interface.md section 7)");
    }
    check_keys(root, "", {"rack", "rt"});
    const toml::table* rack = sub_table(root, "", "rack");
    check_keys(*rack, "rack", {kRackModulesKey.key});
    Config rt;  // the rack's [rt], given to every module
    read_rt_section(*this, sub_table(root, "", "rt"), rt);
    RackConfig r{file(), true, {}};
    for (const std::string& path : module_paths(*rack)) {
      Config m = load_module(path);
      m.rt_priority = rt.rt_priority;
      m.rt_cpu = rt.rt_cpu;
      m.late_limit_ns = rt.late_limit_ns;
      r.modules.push_back(std::move(m));
    }
    return r;
  }

 private:
  // rack.modules: 1 … 16 file names, each absolute or relative to the rack file's folder.
  std::vector<std::string> module_paths(const toml::table& rack) const {
    const ConfigKey& k = kRackModulesKey;
    const toml::node* n = rack.get(k.key);
    const std::string what = "must be a list of " + std::to_string(k.min) + " … " +
                             std::to_string(k.max) + " module file names, e.g. [\"x.toml\", " +
                             "\"y.toml\"]";
    if (n == nullptr) fail(rack.source(), "rack.modules", "required: " + what);
    const toml::array* list = n->as_array();
    const auto size = list != nullptr ? static_cast<std::int64_t>(list->size()) : 0;
    if (list == nullptr || size < k.min || size > k.max) fail(n->source(), "rack.modules", what);
    const std::filesystem::path folder = std::filesystem::path(file()).parent_path();
    std::vector<std::string> paths;
    for (const toml::node& e : *list) {
      const auto* s = e.as_string();
      if (s == nullptr || s->get().empty()) fail(e.source(), "rack.modules", what);
      const std::filesystem::path p(s->get());
      paths.push_back(p.is_absolute() ? p.string() : (folder / p).lexically_normal().string());
    }
    return paths;
  }

  // A module file as its own daemon reads it; an [rt] table in it is an error naming both files.
  Config load_module(const std::string& path) const {
    Config m;
    try {
      m = load_config(path);
    } catch (const ConfigError& e) {
      throw ConfigError(std::string(e.what()) + " (a module file of the rack " + file() + ")");
    }
    if (m.rt_table_line != 0) {
      throw ConfigError(path + ":" + std::to_string(m.rt_table_line) +
                        ": key 'rt': a module file of a rack has no [rt] table, not even an "
                        "empty one: the [rt] of the rack " +
                        file() + " applies to every axis of every module");
    }
    return m;
  }
};

}  // namespace

RackConfig load_rack(const std::string& path) {
  const std::string text = read_config_file(path);
  const toml::table root = ConfigReader(path).parse(text);
  if (root.get("rack") == nullptr) return {path, false, {parse_config(text, path)}};
  RackConfig r = RackParser(path).run(root);
  check_rack(r);
  return r;
}

}  // namespace stepmod::tools

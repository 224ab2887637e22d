#pragma once
// Where the doctor's probes read the kernel's files: "/" on the machine, a directory holding a
// fake proc/ and sys/ in tests. Every probe takes one, so each can be tested on files of its own.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace stepmod::doctor {

class SysRoot {
 public:
  // "" or "/": the machine itself.
  explicit SysRoot(std::string root = "");

  // `path` is absolute ("/proc/sys/kernel/version"): the file under the root.
  std::string path(std::string_view path) const;
  // The whole file, or nullopt when it cannot be read (absent, no permission).
  std::optional<std::string> read(std::string_view path) const;
  // The first line of the file without its newline, or nullopt.
  std::optional<std::string> read_line(std::string_view path) const;
  // The names in a directory (no "." or ".."), sorted; empty when it cannot be read.
  std::vector<std::string> list(std::string_view dir) const;
  bool is_machine() const noexcept { return root_.empty(); }

 private:
  std::string root_;  // without a trailing '/'; "" for the machine
};

}  // namespace stepmod::doctor

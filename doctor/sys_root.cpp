#include "doctor/sys_root.hpp"

#include <dirent.h>

#include <algorithm>
#include <fstream>
#include <sstream>

namespace stepmod::doctor {

SysRoot::SysRoot(std::string root) : root_(std::move(root)) {
  while (!root_.empty() && root_.back() == '/') root_.pop_back();
}

std::string SysRoot::path(std::string_view p) const {
  return root_ + std::string(p);
}

std::optional<std::string> SysRoot::read(std::string_view p) const {
  std::ifstream f(path(p));
  if (!f) return std::nullopt;
  std::stringstream s;
  s << f.rdbuf();
  if (f.bad()) return std::nullopt;
  return s.str();
}

std::optional<std::string> SysRoot::read_line(std::string_view p) const {
  auto text = read(p);
  if (!text) return std::nullopt;
  const auto nl = text->find('\n');
  if (nl != std::string::npos) text->resize(nl);
  return text;
}

std::vector<std::string> SysRoot::list(std::string_view dir) const {
  std::vector<std::string> names;
  DIR* d = opendir(path(dir).c_str());
  if (d == nullptr) return names;
  while (const dirent* e = readdir(d)) {
    const std::string n = e->d_name;
    if (n != "." && n != "..") names.push_back(n);
  }
  closedir(d);
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace stepmod::doctor

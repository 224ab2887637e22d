// The online CPUs and the check of `[rt] cpu` (rt/cpus_online.hpp).
#include "rt/cpus_online.hpp"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <sstream>

namespace stepmod::rt {

namespace {

std::optional<int> number(std::string_view s) {
  int v = -1;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc{} || end != s.data() + s.size() || v < 0) return std::nullopt;
  return v;
}

}  // namespace

std::optional<std::vector<int>> parse_cpu_list(std::string_view text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.remove_suffix(1);
  std::vector<int> cpus;
  while (!text.empty()) {
    const std::size_t comma = text.find(',');
    const std::string_view item = text.substr(0, comma);
    text = comma == std::string_view::npos ? std::string_view{} : text.substr(comma + 1);
    const std::size_t dash = item.find('-');
    const auto first = number(item.substr(0, dash));
    const auto last = dash == std::string_view::npos ? first : number(item.substr(dash + 1));
    if (!first || !last || *last < *first) return std::nullopt;
    for (int c = *first; c <= *last; ++c) cpus.push_back(c);
  }
  if (cpus.empty()) return std::nullopt;
  return cpus;
}

std::optional<std::vector<int>> cpus_online(const std::string& file) {
  std::ifstream in(file);
  std::stringstream text;
  if (!(text << in.rdbuf())) return std::nullopt;
  return parse_cpu_list(text.str());
}

std::string rt_cpu_problem(int cpu, const std::vector<int>& online) {
  if (cpu < 0 || std::find(online.begin(), online.end(), cpu) != online.end()) return "";
  std::string list;
  for (int c : online) list += (list.empty() ? "" : ", ") + std::to_string(c);
  return "CPU " + std::to_string(cpu) + " is not online on this machine (CPUs " + list +
         "; /sys/devices/system/cpu/online): name one of them, or -1 for no pinning";
}

}  // namespace stepmod::rt

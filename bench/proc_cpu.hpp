#pragma once
// The CPU a process has used, from /proc (schedstat: nanoseconds on a CPU, per thread): the daemon
// benchmarks' CPU figures (bench/daemon_bench.cpp, bench/rack_bench.cpp).
#include <dirent.h>
#include <sys/types.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace stepmod::bench {

// CPU ns of every thread of `pid`, keyed "<thread name>/<tid>". Empty once the process is gone.
inline std::map<std::string, double> thread_cpu(pid_t pid) {
  std::map<std::string, double> out;
  const std::string base = "/proc/" + std::to_string(pid) + "/task";
  DIR* dir = opendir(base.c_str());
  if (dir == nullptr) return out;
  while (dirent* e = readdir(dir)) {
    if (e->d_name[0] == '.') continue;
    const std::string t = base + "/" + e->d_name;
    std::string comm;
    std::getline(std::ifstream(t + "/comm"), comm);
    double ns = 0;
    std::ifstream(t + "/schedstat") >> ns;
    out[comm + "/" + e->d_name] += ns;
  }
  closedir(dir);
  return out;
}

inline double total(const std::map<std::string, double>& m) {
  double s = 0;
  for (const auto& [k, v] : m) s += v;
  return s;
}

}  // namespace stepmod::bench

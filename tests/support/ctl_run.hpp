#pragma once
// Runs the stepmodctl program (STEPMODCTL_PATH, from the test's CMake target) to completion with
// `args` and returns its exit status, stdout and stderr.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace stepmod::testing {

struct CtlRun {
  int exit_status = -1;
  std::string out;
  std::string err;
};

inline std::string slurp_file(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

inline CtlRun stepmodctl(const std::string& args) {
  const std::string base = "/tmp/stepmodctl-test-" + std::to_string(::getpid());
  const std::string cmd =
      std::string(STEPMODCTL_PATH) + " " + args + " >" + base + ".out 2>" + base + ".err";
  CtlRun r;
  const int rc = std::system(cmd.c_str());
  r.exit_status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  r.out = slurp_file(base + ".out");
  r.err = slurp_file(base + ".err");
  std::remove((base + ".out").c_str());
  std::remove((base + ".err").c_str());
  return r;
}

}  // namespace stepmod::testing

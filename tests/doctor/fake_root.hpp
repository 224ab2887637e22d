#pragma once
// A temporary directory standing in for / (proc, sys, etc, dev) for the doctor's probes.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace stepmod::testing {

class FakeRoot {
 public:
  FakeRoot() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "stepmod-root-XXXXXX").string();
    dir_ = ::mkdtemp(tmpl.data());
  }
  ~FakeRoot() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  FakeRoot(const FakeRoot&) = delete;
  FakeRoot& operator=(const FakeRoot&) = delete;

  const std::string& dir() const { return dir_; }
  std::string path(const std::string& abs) const { return dir_ + abs; }
  // Writes `text` at `abs` (an absolute path as on the machine) under the root.
  void write(const std::string& abs, const std::string& text) const {
    std::filesystem::create_directories(std::filesystem::path(path(abs)).parent_path());
    std::ofstream(path(abs)) << text;
  }
  bool exists(const std::string& abs) const { return std::filesystem::exists(path(abs)); }
  std::string read(const std::string& abs) const {
    std::ifstream f(path(abs));
    return std::string(std::istreambuf_iterator<char>(f), {});
  }

 private:
  std::string dir_;
};

}  // namespace stepmod::testing

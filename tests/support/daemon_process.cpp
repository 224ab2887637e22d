#include "tests/support/daemon_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include "ipc/stepmod_image.h"

namespace stepmod::testing {

namespace {

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size())) {
    s.replace(p, from.size(), to);
  }
  return s;
}

// Starts `argv` with stderr (and stdout) appended to `log`. In a cross build the tests run under
// qemu-user and so is the daemon: STEPMOD_TEST_EMULATOR (set by ctest from
// CMAKE_CROSSCOMPILING_EMULATOR, words separated by spaces) goes in front of the program, since
// without binfmt_misc the kernel cannot start a foreign binary by itself.
// The child is killed when this process dies (PR_SET_PDEATHSIG): a test process that ends
// without its destructors (a sanitizer's halt, a ctest timeout) must not leave a real-time
// daemon running. One would hold its image name, t<pid>-<n>, and a later test process given
// the same pid would have its daemon refused that name.
pid_t spawn(const std::vector<std::string>& program_args, const std::string& log) {
  std::vector<std::string> args;
  if (const char* emu = std::getenv("STEPMOD_TEST_EMULATOR"); emu != nullptr && *emu != '\0') {
    std::istringstream words(emu);
    for (std::string w; words >> w;) args.push_back(w);
  }
  args.insert(args.end(), program_args.begin(), program_args.end());
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const int out = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (out < 0) throw std::runtime_error("cannot open " + log);
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid == 0) {
    // The child of a threaded process: async-signal-safe calls only, up to the exec.
    if (prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || getppid() != parent) _exit(127);
    if (dup2(out, 1) < 0 || dup2(out, 2) < 0) _exit(127);
    execve(argv[0], argv.data(), environ);
    constexpr char kFailed[] = "spawn: execve failed: ";
    (void)!write(2, kFailed, sizeof kFailed - 1);
    (void)!write(2, argv[0], std::strlen(argv[0]));
    (void)!write(2, "\n", 1);
    _exit(127);
  }
  ::close(out);
  if (pid < 0) throw std::runtime_error("cannot start " + args[0]);
  return pid;
}

int wait_exit(pid_t pid, int timeout_ms) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  while (std::chrono::steady_clock::now() < end) {
    int status = 0;
    const pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return -1;
}

// What a test needs of the header of an image or panel file in /dev/shm. nullopt while there is
// no whole one (not created yet, or between the unlink of a stale one and its replacement).
struct ShmHead {
  std::uint64_t owner_pid = 0;
  std::uint64_t scans = 0;  // the image's scan counter (0 for a panel)
};

template <typename Header>
std::optional<Header> read_header(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  Header h{};
  const ssize_t n = ::pread(fd, &h, sizeof h, 0);
  ::close(fd);
  if (n != static_cast<ssize_t>(sizeof h)) return std::nullopt;
  return h;
}

std::optional<ShmHead> image_head(const std::string& path) {
  const auto im = read_header<stepmod_image_t>(path);
  if (!im || stepmod_magic_is(im->magic, STEPMOD_IMAGE_MAGIC) == 0) return std::nullopt;
  return ShmHead{im->owner_pid, im->scan_counter};
}

std::optional<ShmHead> panel_head(const std::string& path) {
  const auto p = read_header<stepmod_panel_t>(path);
  if (!p || stepmod_magic_is(p->magic, STEPMOD_PANEL_MAGIC) == 0) return std::nullopt;
  return ShmHead{p->owner_pid, 0};
}

// Removes `path` if the daemon `pid` owns it: a killed daemon cannot remove its own files, and
// one left behind would be found by a later test whose process got the same pid (the same
// unique name). A file another daemon of the name owns now is left alone.
void remove_if_owned(const std::optional<ShmHead>& head, const std::string& path, pid_t pid) {
  if (head && head->owner_pid == static_cast<std::uint64_t>(pid)) ::unlink(path.c_str());
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

std::string DaemonProcess::daemon_path() {
  return STEPMOD_DAEMON_PATH;
}

DaemonProcess::DaemonProcess(const std::string& toml, const DaemonOptions& options) {
  static std::atomic<int> counter{0};
  char tmpl[] = "/tmp/stepmod-test-XXXXXX";
  if (mkdtemp(tmpl) == nullptr) throw std::runtime_error("mkdtemp failed");
  dir_ = tmpl;
  // Formatted with snprintf: building it with std::string operator+ / += of std::to_string
  // trips GCC 12's -O3 -Wrestrict false positive inside libstdc++ (a Release build with
  // -Werror failed on it).
  char unique[64];
  std::snprintf(unique, sizeof unique, "t%ld-%d", static_cast<long>(getpid()), counter++);
  name_ = options.name.empty() ? std::string(unique) : options.name;
  config_ = dir_ + "/module.toml";
  trace_ = options.trace_path.empty() ? dir_ + "/trace.vcd" : options.trace_path;
  log_ = dir_ + "/stepmodd.log";
  std::ofstream(config_) << replace_all(toml, "{NAME}", name_);
  std::vector<std::string> args{options.exe.empty() ? daemon_path() : options.exe, "--config",
                                config_};
  if (options.trace) {
    args.push_back("--trace");
    args.push_back(trace_);
  }
  pid_ = spawn(args, log_);
  spawned_ = pid_;
}

DaemonProcess::~DaemonProcess() {
  if (pid_ > 0) {
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
  const std::string image = "/dev/shm/stepmod." + name_;
  remove_if_owned(image_head(image), image, spawned_);
  remove_if_owned(panel_head(image + ".sim"), image + ".sim", spawned_);
  std::error_code ec;
  if (std::getenv("STEPMOD_KEEP_TEST_FILES") == nullptr) std::filesystem::remove_all(dir_, ec);
}

bool DaemonProcess::wait_ready(int timeout_ms) {
  // Up means the image names this daemon as its owner and a scan has been published. The file
  // alone is not enough: one a killed daemon of the same name left is there before this daemon
  // replaces it, and a client that mapped it would wait for scans that never come.
  const std::string shm = "/dev/shm/stepmod." + name_;
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  while (std::chrono::steady_clock::now() < end) {
    const std::optional<ShmHead> head = image_head(shm);
    if (head && head->owner_pid == static_cast<std::uint64_t>(pid_) && head->scans > 0) {
      return true;
    }
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

int DaemonProcess::terminate(int timeout_ms) {
  if (pid_ <= 0) return -1;
  kill(pid_, SIGTERM);
  const int rc = stepmod::testing::wait_exit(pid_, timeout_ms);
  if (rc >= 0) pid_ = -1;
  return rc;
}

void DaemonProcess::signal(int sig) {
  if (pid_ > 0) kill(pid_, sig);
}

int DaemonProcess::wait_exit(int timeout_ms) {
  if (pid_ <= 0) return -1;
  const int rc = stepmod::testing::wait_exit(pid_, timeout_ms);
  if (rc >= 0) pid_ = -1;
  return rc;
}

std::string DaemonProcess::log() const {
  return read_file(log_);
}

int DaemonProcess::run_to_exit(const std::string& args, std::string* stderr_text) {
  char tmpl[] = "/tmp/stepmod-run-XXXXXX";
  if (mkdtemp(tmpl) == nullptr) throw std::runtime_error("mkdtemp failed");
  const std::string log = std::string(tmpl) + "/log";
  std::vector<std::string> argv{daemon_path()};
  std::istringstream ss(args);
  for (std::string a; ss >> a;) argv.push_back(a);
  const pid_t pid = spawn(argv, log);
  const int rc = stepmod::testing::wait_exit(pid, 10'000);
  if (rc < 0) {
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
  }
  if (stderr_text != nullptr) *stderr_text = read_file(log);
  std::error_code ec;
  std::filesystem::remove_all(tmpl, ec);
  return rc;
}

}  // namespace stepmod::testing

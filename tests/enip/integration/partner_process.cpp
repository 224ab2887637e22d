#include "tests/enip/integration/partner_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <regex>
#include <thread>

#include "tests/support/shell.hpp"

namespace stepmod::testing {

namespace {
using Clock = std::chrono::steady_clock;
}  // namespace

bool in_ci() {
  const char* ci = std::getenv("CI");
  return ci != nullptr && (std::string(ci) == "true" || std::string(ci) == "1");
}

std::string enip_partners_missing() {
  std::string out;
  if (run_shell("node --version", &out) != 0) {
    return "node cannot run here (scripts/install-deps installs nodejs): " + out;
  }
  const std::filesystem::path mods(STEPMOD_ENIP_PARTNERS);
  if (!std::filesystem::exists(mods / "st-ethernet-ip") ||
      !std::filesystem::exists(mods / "ethernet-ip")) {
    return "the EtherNet/IP test partners are not installed in " + mods.string() +
           ": run scripts/install-deps --enip-partners " +
           mods.parent_path().parent_path().string();
  }
  return "";
}

PartnerProcess::PartnerProcess(const std::vector<std::string>& args) {
  int to_child[2];
  int from_child[2];
  if (::pipe2(to_child, O_CLOEXEC) != 0 || ::pipe2(from_child, O_CLOEXEC) != 0) return;
  std::vector<std::string> argv{"node", STEPMOD_ENIP_PARTNER_JS};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> cargv;
  for (std::string& a : argv) cargv.push_back(a.data());
  cargv.push_back(nullptr);
  const std::string node_path = std::string("NODE_PATH=") + STEPMOD_ENIP_PARTNERS;
  pid_ = ::fork();
  if (pid_ == 0) {
    ::dup2(to_child[0], 0);
    ::dup2(from_child[1], 1);
    ::putenv(const_cast<char*>(node_path.c_str()));
    ::execvp("node", cargv.data());
    ::_exit(127);
  }
  ::close(to_child[0]);
  ::close(from_child[1]);
  in_ = to_child[1];
  out_ = from_child[0];
}

PartnerProcess::~PartnerProcess() {
  if (in_ >= 0) ::close(in_);
  if (pid_ > 0) {
    const auto end = Clock::now() + std::chrono::seconds(2);
    int st = 0;
    while (::waitpid(pid_, &st, WNOHANG) == 0) {
      if (Clock::now() > end) {
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, &st, 0);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  if (out_ >= 0) ::close(out_);
}

void PartnerProcess::send(const std::string& line) {
  const std::string l = line + "\n";
  [[maybe_unused]] const ssize_t n = ::write(in_, l.data(), l.size());
}

std::optional<std::string> PartnerProcess::line(std::chrono::milliseconds timeout) {
  const auto end = Clock::now() + timeout;
  for (;;) {
    if (const auto nl = buffer_.find('\n'); nl != std::string::npos) {
      std::string l = buffer_.substr(0, nl);
      buffer_.erase(0, nl + 1);
      transcript_ += l + "\n";
      return l;
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - Clock::now());
    if (left.count() <= 0) return std::nullopt;
    pollfd p{out_, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
    char buf[4096];
    const ssize_t n = ::read(out_, buf, sizeof buf);
    if (n <= 0) return std::nullopt;
    buffer_.append(buf, static_cast<std::size_t>(n));
  }
}

std::optional<std::string> PartnerProcess::line_with(const std::string& needle,
                                                     std::chrono::milliseconds timeout) {
  const auto end = Clock::now() + timeout;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - Clock::now());
    if (left.count() <= 0) return std::nullopt;
    auto l = line(left);
    if (!l) return std::nullopt;
    if (l->find(needle) != std::string::npos) return l;
  }
}

std::optional<std::string> PartnerProcess::ask(const std::string& cmd,
                                               std::chrono::milliseconds timeout) {
  send(cmd);
  return line(timeout);
}

std::string json_field(const std::string& json, const std::string& key) {
  const std::regex re("\"" + key + "\":(\"([^\"]*)\"|([^,}\\]]*))");
  std::smatch m;
  if (!std::regex_search(json, m, re)) return "";
  return m[2].matched ? m[2].str() : m[3].str();
}

}  // namespace stepmod::testing

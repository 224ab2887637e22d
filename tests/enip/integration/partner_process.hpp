#pragma once
// One run of tests/enip/integration/partner.js (the npm EtherNet/IP clients) as a child process:
// lines to its stdin, JSON lines from its stdout, read with a timeout. And whether the partners
// can run here: without node a test skips, saying so (in CI, CI=true, it fails instead: CI must
// run them); node without the installed partners is an error naming the command that installs
// them.
#include <sys/types.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace stepmod::testing {

// "" when the partners can run; else why not.
std::string enip_partners_missing();
bool in_ci();

#define REQUIRE_ENIP_PARTNERS()                                                            \
  if (const std::string why = ::stepmod::testing::enip_partners_missing(); !why.empty()) { \
    if (::stepmod::testing::in_ci() || why.rfind("node cannot run", 0) != 0) {             \
      FAIL() << why;                                                                       \
    }                                                                                      \
    GTEST_SKIP() << why;                                                                   \
  }

class PartnerProcess {
 public:
  explicit PartnerProcess(const std::vector<std::string>& args);
  ~PartnerProcess();  // closes its stdin, then kills it if it has not ended
  PartnerProcess(const PartnerProcess&) = delete;
  PartnerProcess& operator=(const PartnerProcess&) = delete;

  void send(const std::string& line);
  // The next line of its stdout; nullopt after `timeout` or at its end.
  std::optional<std::string> line(std::chrono::milliseconds timeout);
  // The next line containing `needle` (others are skipped and kept in transcript()).
  std::optional<std::string> line_with(const std::string& needle,
                                       std::chrono::milliseconds timeout);
  // Sends `cmd` and returns the next line (the reply).
  std::optional<std::string> ask(const std::string& cmd,
                                 std::chrono::milliseconds timeout = std::chrono::seconds(5));
  const std::string& transcript() const { return transcript_; }

 private:
  pid_t pid_ = -1;
  int in_ = -1;
  int out_ = -1;
  std::string buffer_;
  std::string transcript_;
};

// The value of `"key":` in a one-line JSON object: a string's text, or a number's/literal's
// text; "" when absent.
std::string json_field(const std::string& json, const std::string& key);

}  // namespace stepmod::testing

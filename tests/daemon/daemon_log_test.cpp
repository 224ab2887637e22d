// stepmodd's log under the journal (docs/interface.md 1): JOURNAL_STREAM naming stderr's device and
// inode turns on the sd-daemon priority prefixes.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include "daemon/daemon_log.hpp"

namespace stepmod::tools {
namespace {

TEST(DaemonLog, JournalStreamMustNameTheDescriptorsFile) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  struct stat st {};
  ASSERT_EQ(::fstat(::fileno(f), &st), 0);
  const std::string mine = std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
  EXPECT_TRUE(is_journal_stream(mine.c_str(), ::fileno(f)));
  const std::string other = std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino + 1);
  EXPECT_FALSE(is_journal_stream(other.c_str(), ::fileno(f)));
  EXPECT_FALSE(is_journal_stream(nullptr, ::fileno(f)));
  EXPECT_FALSE(is_journal_stream("garbage", ::fileno(f)));
  std::fclose(f);
}

TEST(DaemonLog, SyslogPrioritiesOfTheLevels) {
  EXPECT_STREQ(syslog_prefix(spdlog::level::err), "<3>");
  EXPECT_STREQ(syslog_prefix(spdlog::level::warn), "<4>");
  EXPECT_STREQ(syslog_prefix(spdlog::level::info), "<6>");
  EXPECT_STREQ(syslog_prefix(spdlog::level::debug), "<7>");
  EXPECT_STREQ(syslog_prefix(spdlog::level::critical), "<2>");
}

}  // namespace
}  // namespace stepmod::tools

#include "daemon/daemon_log.hpp"

#include <spdlog/pattern_formatter.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cinttypes>
#include <cstdio>
#include <cstdlib>

namespace stepmod::tools {

namespace {
// "%*": the level's syslog prefix.
class PriorityFlag final : public spdlog::custom_flag_formatter {
 public:
  void format(const spdlog::details::log_msg& msg, const std::tm& /*tm*/,
              spdlog::memory_buf_t& dest) override {
    const std::string_view p = syslog_prefix(msg.level);
    dest.append(p.data(), p.data() + p.size());
  }
  std::unique_ptr<custom_flag_formatter> clone() const override {
    return spdlog::details::make_unique<PriorityFlag>();
  }
};

thread_local std::string t_scope;  // set_log_scope

// "%&": the logging thread's scope (a rack's module), or nothing.
class ScopeFlag final : public spdlog::custom_flag_formatter {
 public:
  void format(const spdlog::details::log_msg& /*msg*/, const std::tm& /*tm*/,
              spdlog::memory_buf_t& dest) override {
    dest.append(t_scope.data(), t_scope.data() + t_scope.size());
  }
  std::unique_ptr<custom_flag_formatter> clone() const override {
    return spdlog::details::make_unique<ScopeFlag>();
  }
};
}  // namespace

void set_log_scope(std::string scope) {
  t_scope = std::move(scope);
}

bool is_journal_stream(const char* journal_stream, int fd) {
  if (journal_stream == nullptr) return false;
  std::uintmax_t dev = 0;
  std::uintmax_t ino = 0;
  if (std::sscanf(journal_stream, "%" SCNuMAX ":%" SCNuMAX, &dev, &ino) != 2) return false;
  struct stat st {};
  if (::fstat(fd, &st) != 0) return false;
  return static_cast<std::uintmax_t>(st.st_dev) == dev &&
         static_cast<std::uintmax_t>(st.st_ino) == ino;
}

const char* syslog_prefix(spdlog::level::level_enum level) noexcept {
  switch (level) {
    case spdlog::level::trace:
    case spdlog::level::debug:
      return "<7>";
    case spdlog::level::info:
      return "<6>";
    case spdlog::level::warn:
      return "<4>";
    case spdlog::level::err:
      return "<3>";
    case spdlog::level::critical:
      return "<2>";
    case spdlog::level::off:
    case spdlog::level::n_levels:
      break;
  }
  return "<6>";
}

std::shared_ptr<spdlog::logger> make_daemon_logger() {
  const bool journal = is_journal_stream(std::getenv("JOURNAL_STREAM"), STDERR_FILENO);
  auto logger =
      journal ? spdlog::stderr_logger_mt("stepmodd") : spdlog::stderr_color_mt("stepmodd");
  auto f = std::make_unique<spdlog::pattern_formatter>();
  f->add_flag<PriorityFlag>('*').add_flag<ScopeFlag>('&');
  // spdlog's own "%+" with the scope before the text.
  f->set_pattern(journal ? "%*%&%v" : "[%Y-%m-%d %H:%M:%S.%e] [%n] [%^%l%$] %&%v");
  logger->set_formatter(std::move(f));
  spdlog::set_default_logger(logger);
  return logger;
}

}  // namespace stepmod::tools

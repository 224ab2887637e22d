#pragma once
// stepmodd's logger (docs/interface.md 1): spdlog on stderr. When stderr is the systemd journal
// (JOURNAL_STREAM names stderr's device and inode, systemd.exec(5)) every line starts with its
// syslog priority, sd-daemon(3) style ("<4>" for a warning), so `journalctl -p warning` finds
// faults; the journal adds its own time stamp. Elsewhere: colours and a time stamp as before.
#include <memory>
#include <string>

#include <spdlog/logger.h>

namespace stepmod::tools {

// Whether `journal_stream` ("DEV:INODE", the JOURNAL_STREAM variable) names the file open on
// descriptor `fd`.
bool is_journal_stream(const char* journal_stream, int fd);

// The "<N>" syslog priority prefix of a spdlog level (sd-daemon.h: SD_ERR = <3>, ...).
const char* syslog_prefix(spdlog::level::level_enum level) noexcept;

// The calling thread's scope: every line it logs starts with `scope` ("[x] ": the module whose
// control thread it is, in a rack); "" (the default) for none.
void set_log_scope(std::string scope);

// Creates the "stepmodd" logger on stderr as described above and makes it the default.
std::shared_ptr<spdlog::logger> make_daemon_logger();

}  // namespace stepmod::tools

#pragma once
// How the trace writes its files (docs/hardening.md): never through a name it did not create.
// A trace path is given on a command line, often in a shared directory (/tmp), where anyone may
// have planted a symbolic link, a hard link or a FIFO under the name beforehand. So every file
// is created new (O_CREAT | O_EXCL | O_NOFOLLOW: an existing name, a dangling link included, is
// an error rather than something followed or truncated; or O_TMPFILE: no name at all), written
// and read back through the descriptor it was created with (never reopened by name: a FIFO
// planted later cannot block the trace thread), and the VCD is renamed into place at the end (a
// link planted at its name is replaced, not followed; a hard-linked file keeps its contents).
#include <sys/types.h>

#include <string>

namespace stepmod::gpio {

// "a symbolic link", "a FIFO", "a directory", ... for an error message.
std::string file_type_name(mode_t mode);

// Throws std::runtime_error ("<what> '<path>': ... not a regular file") if `path` exists and is
// not a regular file; does nothing if it does not exist or is one. Never follows a link.
void refuse_special_file(const std::string& path, const char* what);

// Creates `path` as a new file, read-write, close-on-exec, non-blocking; throws naming it and
// saying what is in the way if the name exists. The descriptor is the caller's to close.
int create_new_file(const std::string& path, const char* what);

// A new file beside `path` (same directory, so that it can be renamed there) that becomes `path`
// once complete (put_in_place()). Where the filesystem allows (O_TMPFILE, and /proc to link it
// later), it has no name at all until then: there is nothing to guess, plant or leave behind.
// Otherwise its name is random, "<path>.tmp.<16 hex digits>" from getrandom(), created with
// O_EXCL | O_NOFOLLOW (a name that exists, planted or not, is skipped for a fresh one, never
// opened). A predictable "<path>.tmp.<pid>.<n>" once let anyone make the trace fail by planting
// the hundred names it would try.
struct NewFile {
  int fd = -1;
  std::string path;  // its name; empty while it has none (O_TMPFILE)
};
enum class Naming {
  kUnnamedIfPossible,
  kRandomName,  // never O_TMPFILE (what a filesystem without it gets; for tests)
};
NewFile create_file_beside(const std::string& path, const char* what,
                           Naming naming = Naming::kUnnamedIfPossible);

// Gives the complete file the name `path`, replacing whatever has that name (a link there is
// replaced, never followed). An unnamed file is first linked to a random name beside `path`
// (linkat(2), which never replaces or follows an existing name), then renamed. Throws naming
// `path` (the file's own name removed). Either way the descriptor is closed and `file` emptied.
void put_in_place(NewFile& file, const std::string& path, const char* what);

// Closes the descriptor and removes the file's name, if it has one; `file` is emptied.
void discard(NewFile& file) noexcept;

// Opens an existing regular file for reading, without following a link and without blocking
// on a FIFO (which is then refused); throws naming it.
int open_regular_for_reading(const std::string& path, const char* what);

}  // namespace stepmod::gpio

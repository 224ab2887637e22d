#include "gpio/trace_file.hpp"

#include <fcntl.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <stdexcept>

namespace stepmod::gpio {

namespace {
[[noreturn]] void fail(const char* what, const std::string& path, const std::string& why) {
  throw std::runtime_error(std::string(what) + " '" + path + "': " + why);
}

// What is in the way of a new file at `path` (after EEXIST), for the message.
std::string existing_what(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return "exists";
  if (S_ISREG(st.st_mode)) return "exists (a regular file)";
  return "exists and is " + file_type_name(st.st_mode) + ", not a regular file";
}
}  // namespace

std::string file_type_name(mode_t mode) {
  if (S_ISLNK(mode)) return "a symbolic link";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISREG(mode)) return "a regular file";
  return "a special file";
}

void refuse_special_file(const std::string& path, const char* what) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) return;
    fail(what, path, std::strerror(errno));
  }
  if (!S_ISREG(st.st_mode)) {
    fail(what, path, "is " + file_type_name(st.st_mode) + ", not a regular file: refused");
  }
}

int create_new_file(const std::string& path, const char* what) {
  const int fd =
      ::open(path.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK, 0644);
  if (fd >= 0) return fd;
  if (errno == EEXIST) fail(what, path, existing_what(path));
  fail(what, path, std::string("cannot create: ") + std::strerror(errno));
}

namespace {

// Names tried before giving up: each is 64 random bits, so a clash means something is wrong with
// the directory or the randomness, not someone's planted file.
constexpr int kNameTries = 16;

// "<path>.tmp.<16 hex digits>": from getrandom(); should the kernel not give any (no entropy yet
// at early boot, no getrandom()), from the clock and a counter -- still no name another user
// can list in advance, and O_EXCL / linkat() refuse an existing one anyway.
std::string random_name(const std::string& path) {
  static std::atomic<std::uint64_t> counter{0};
  std::uint64_t v = 0;
  if (::getrandom(&v, sizeof v, GRND_NONBLOCK) != static_cast<ssize_t>(sizeof v)) {
    timespec ts{};
    ::clock_gettime(CLOCK_MONOTONIC, &ts);
    v = (static_cast<std::uint64_t>(ts.tv_sec) << 30) ^ static_cast<std::uint64_t>(ts.tv_nsec) ^
        (counter.fetch_add(1, std::memory_order_relaxed) * 0x9E3779B97F4A7C15ull) ^
        (static_cast<std::uint64_t>(::getpid()) << 40);
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(v));
  return path + ".tmp." + hex;
}

std::string directory_of(const std::string& path) {
  const auto slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

// An O_TMPFILE file in `path`'s directory that put_in_place() can link (through /proc), or -1.
int unnamed_file(const std::string& path) {
  const int fd = ::open(directory_of(path).c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0644);
  if (fd < 0) return -1;  // no O_TMPFILE here (EOPNOTSUPP, EISDIR...): a named file instead
  const std::string proc = "/proc/self/fd/" + std::to_string(fd);
  if (::access(proc.c_str(), F_OK) != 0) {
    ::close(fd);  // no /proc: it could never be given a name
    return -1;
  }
  return fd;
}

// Links the unnamed file `fd` to `name`: 0, or the errno.
int link_unnamed(int fd, const std::string& name) {
  const std::string proc = "/proc/self/fd/" + std::to_string(fd);
  if (::linkat(AT_FDCWD, proc.c_str(), AT_FDCWD, name.c_str(), AT_SYMLINK_FOLLOW) == 0) return 0;
  const int err = errno;
  // Without /proc after all, a process with CAP_DAC_READ_SEARCH can still link it directly.
  if (err != EEXIST && ::linkat(fd, "", AT_FDCWD, name.c_str(), AT_EMPTY_PATH) == 0) return 0;
  return err;
}

// Gives the unnamed `file` a random name beside `path`.
void name_unnamed(NewFile& file, const std::string& path, const char* what) {
  for (int attempt = 0;; ++attempt) {
    const std::string name = random_name(path);
    const int err = link_unnamed(file.fd, name);
    if (err == 0) {
      file.path = name;
      return;
    }
    if (err != EEXIST || attempt + 1 >= kNameTries) {
      discard(file);
      fail(what, path, "cannot name the new file beside it (" + name + "): " + std::strerror(err));
    }
  }
}

}  // namespace

NewFile create_file_beside(const std::string& path, const char* what, Naming naming) {
  if (naming == Naming::kUnnamedIfPossible) {
    if (const int fd = unnamed_file(path); fd >= 0) return {fd, {}};
  }
  for (int attempt = 0;; ++attempt) {
    const std::string tmp = random_name(path);
    const int fd =
        ::open(tmp.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK, 0644);
    if (fd >= 0) return {fd, tmp};
    // Something under that name (a 64-bit random one): take another.
    if (errno != EEXIST || attempt + 1 >= kNameTries) {
      fail(what, path, "cannot create a file beside it (" + tmp + "): " + std::strerror(errno));
    }
  }
}

void put_in_place(NewFile& file, const std::string& path, const char* what) {
  if (file.path.empty()) name_unnamed(file, path, what);
  // Replaces the name, never what a link there points to.
  if (::rename(file.path.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    discard(file);
    fail(what, path, "cannot put it in place: " + why);
  }
  ::close(file.fd);
  file = NewFile{};
}

void discard(NewFile& file) noexcept {
  if (!file.path.empty()) ::unlink(file.path.c_str());
  if (file.fd >= 0) ::close(file.fd);
  file = NewFile{};
}

int open_regular_for_reading(const std::string& path, const char* what) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) {
    if (errno == ELOOP) fail(what, path, "is a symbolic link: refused");
    fail(what, path, std::string("cannot open: ") + std::strerror(errno));
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    const std::string type = file_type_name(st.st_mode);
    ::close(fd);
    fail(what, path, "is " + type + ", not a regular file: refused");
  }
  return fd;
}

}  // namespace stepmod::gpio

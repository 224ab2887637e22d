#include "gpio/trace_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
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

NewFile create_file_beside(const std::string& path, const char* what) {
  static std::atomic<unsigned> counter{0};
  for (int attempt = 0;; ++attempt) {
    const std::string tmp = path + ".tmp." + std::to_string(::getpid()) + "." +
                            std::to_string(counter.fetch_add(1, std::memory_order_relaxed));
    const int fd =
        ::open(tmp.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK, 0644);
    if (fd >= 0) return {fd, tmp};
    // Someone else's file under that name (planted or left over): take the next name.
    if (errno != EEXIST || attempt >= 100) {
      fail(what, path, "cannot create a file beside it (" + tmp + "): " + std::strerror(errno));
    }
  }
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

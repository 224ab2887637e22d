#include "ipc/shm_object.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "ipc/stepmod_image.h"

namespace stepmod::ipc {
namespace {

std::string errno_text(int e) {
  if (e == EACCES || e == EPERM) return std::string(std::strerror(e)) + " (" + kGroupHint + ")";
  return std::strerror(e);
}

std::string dev_shm_path(const std::string& object) {
  return "/dev/shm" + object;
}

// Closes the descriptor on every path out of create()/open().
struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

enum class Existing { kStale, kAlive, kUnknown };

// What occupies `object` now. Reads it without changing it.
Existing classify_existing(const std::string& object, std::size_t size, std::string_view magic,
                           std::size_t pid_offset, std::uint64_t& pid,
                           std::vector<std::uint8_t>& content) {
  pid = 0;
  Fd f{::shm_open(object.c_str(), O_RDONLY, 0)};
  if (f.fd < 0) return errno == ENOENT ? Existing::kStale : Existing::kUnknown;
  struct stat st {};
  if (::fstat(f.fd, &st) != 0 || static_cast<std::size_t>(st.st_size) < size) {
    return Existing::kUnknown;
  }
  void* p = ::mmap(nullptr, size, PROT_READ, MAP_SHARED, f.fd, 0);
  if (p == MAP_FAILED) return Existing::kUnknown;
  const auto* bytes = static_cast<const unsigned char*>(p);
  const bool magic_ok = std::memcmp(bytes, magic.data(), magic.size()) == 0;
  std::memcpy(&pid, bytes + pid_offset, sizeof pid);
  content.assign(bytes, bytes + size);
  ::munmap(p, size);
  if (!magic_ok || pid == 0 || pid > static_cast<std::uint64_t>(INT32_MAX)) {
    return Existing::kUnknown;
  }
  // The creator holds an exclusive flock on the object for as long as it lives (create()); the
  // kernel drops it when the process ends, however it ends. A lock we can take means nobody
  // serves this image any more, even if the recorded pid now belongs to another process (a pid
  // reused after a crash, which kill(pid, 0) took for the owner).
  if (::flock(f.fd, LOCK_SH | LOCK_NB) == 0) return Existing::kStale;  // released with the fd
  return errno == EWOULDBLOCK ? Existing::kAlive : Existing::kUnknown;
}

}  // namespace

bool valid_name(std::string_view name) noexcept {
  if (name.empty() || name.size() > kMaxNameLength) return false;
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
    if (!ok) return false;
  }
  return true;
}

void check_name(std::string_view name) {
  if (!valid_name(name)) {
    throw IpcError("invalid module name '" + std::string(name) + "': use 1.." +
                   std::to_string(kMaxNameLength) + " characters of a-z, 0-9, '-' and '_'");
  }
}

std::string image_object(std::string_view name) {
  return "/stepmod." + std::string(name);
}
std::string panel_object(std::string_view name) {
  return "/stepmod." + std::string(name) + ".sim";
}

ShmMapping& ShmMapping::operator=(ShmMapping&& o) noexcept {
  if (this != &o) {
    reset();
    addr_ = std::exchange(o.addr_, nullptr);
    size_ = std::exchange(o.size_, 0);
    object_ = std::move(o.object_);
    owner_ = std::exchange(o.owner_, false);
    writable_ = std::exchange(o.writable_, false);
    replaced_pid_ = std::exchange(o.replaced_pid_, 0);
    replaced_ = std::move(o.replaced_);
    lock_fd_ = std::exchange(o.lock_fd_, -1);
  }
  return *this;
}

void ShmMapping::reset() noexcept {
  if (addr_ != nullptr) ::munmap(addr_, size_);
  if (owner_) ::shm_unlink(object_.c_str());
  if (lock_fd_ >= 0) ::close(lock_fd_);  // after the unlink: never a live name without its lock
  lock_fd_ = -1;
  addr_ = nullptr;
  size_ = 0;
  owner_ = false;
  writable_ = false;
}

ShmMapping ShmMapping::create(const std::string& object, std::size_t size, std::string_view magic,
                              std::size_t pid_offset) {
  Fd f;
  std::uint64_t stale_pid = 0;
  std::vector<std::uint8_t> stale;
  // Two attempts: the second one after removing a stale leftover.
  for (int attempt = 0; attempt < 2 && f.fd < 0; ++attempt) {
    f.fd = ::shm_open(object.c_str(), O_RDWR | O_CREAT | O_EXCL, 0660);
    // Locked before anything is written to it: an object whose magic is there is locked while
    // its creator lives.
    if (f.fd >= 0 && ::flock(f.fd, LOCK_EX | LOCK_NB) != 0) {
      const int e = errno;
      ::shm_unlink(object.c_str());
      throw IpcError("cannot lock " + dev_shm_path(object) + ": " + errno_text(e));
    }
    if (f.fd >= 0) break;
    if (errno != EEXIST) {
      throw IpcError("cannot create " + dev_shm_path(object) + ": " + errno_text(errno));
    }
    std::uint64_t pid = 0;
    switch (classify_existing(object, size, magic, pid_offset, pid, stale)) {
      case Existing::kStale:
        ::shm_unlink(object.c_str());  // may race another creator; O_EXCL settles it
        stale_pid = pid;
        continue;
      case Existing::kAlive:
        throw IpcError(dev_shm_path(object) + " is in use by process " + std::to_string(pid) +
                       " (another stepmodd with the same module name?)");
      case Existing::kUnknown:
        throw IpcError(dev_shm_path(object) + " already exists and its owner is unknown; remove " +
                       dev_shm_path(object) + " if no stepmodd runs with this name");
    }
  }
  if (f.fd < 0) throw IpcError("cannot create " + dev_shm_path(object) + ": created concurrently");

  ShmMapping m;
  m.object_ = object;
  m.owner_ = true;  // from here on, a failure unlinks the half-made object
  // The umask would otherwise strip the group write bit the PLC's group needs.
  if (::fchmod(f.fd, 0660) != 0 || ::ftruncate(f.fd, static_cast<off_t>(size)) != 0) {
    const int e = errno;
    m.reset();
    throw IpcError("cannot set up " + dev_shm_path(object) + ": " + errno_text(e));
  }
  void* p = ::mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_SHARED, f.fd, 0);
  if (p == MAP_FAILED) {
    const int e = errno;
    m.reset();
    throw IpcError("cannot map " + dev_shm_path(object) + ": " + errno_text(e));
  }
  m.addr_ = p;
  m.size_ = size;
  m.writable_ = true;
  m.lock_fd_ = std::exchange(f.fd, -1);  // holds the owner's lock until reset()
  if (stale_pid != 0) {
    m.replaced_pid_ = stale_pid;
    m.replaced_ = std::move(stale);
  }
  return m;
}

ShmMapping ShmMapping::open(const std::string& object, std::size_t min_size) {
  Fd f{::shm_open(object.c_str(), O_RDWR, 0)};
  bool writable = true;
  if (f.fd < 0 && errno == EACCES) {
    f.fd = ::shm_open(object.c_str(), O_RDONLY, 0);
    writable = false;
  }
  if (f.fd < 0) {
    if (errno == ENOENT) {
      throw IpcError(dev_shm_path(object) + " does not exist: is stepmodd running with this name?");
    }
    throw IpcError("cannot open " + dev_shm_path(object) + ": " + errno_text(errno));
  }
  struct stat st {};
  if (::fstat(f.fd, &st) != 0 || static_cast<std::size_t>(st.st_size) < min_size) {
    throw IpcError(dev_shm_path(object) + " is too small to be a stepmod object (" +
                   std::to_string(st.st_size) + " bytes)");
  }
  void* p =
      ::mmap(nullptr, min_size, writable ? PROT_READ | PROT_WRITE : PROT_READ, MAP_SHARED, f.fd, 0);
  if (p == MAP_FAILED) {
    throw IpcError("cannot map " + dev_shm_path(object) + ": " + errno_text(errno));
  }
  ShmMapping m;
  m.addr_ = p;
  m.size_ = min_size;
  m.object_ = object;
  m.writable_ = writable;
  return m;
}

void check_header(const std::string& object, const char* magic_field, std::uint32_t version,
                  const ObjectHeader& expect) {
  const std::string path = "/dev/shm" + object;
  if (!stepmod_magic_is(magic_field, expect.magic)) {
    throw IpcError(path + " is not " + expect.what + " (bad magic" + expect.magic_hint + ")");
  }
  if (version != expect.version) {
    throw IpcError(path + " has " + expect.version_name + " version " + std::to_string(version) +
                   ", this program understands version " + std::to_string(expect.version));
  }
}

}  // namespace stepmod::ipc

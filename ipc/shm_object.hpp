#pragma once
// POSIX shared-memory objects of stepmod: names, creation with stale-object recovery, opening.
// Internal to ipc/ (ShmImage, Client and the panel classes build on it), but usable by tests.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace stepmod::ipc {

// Every failure of the ipc layer (missing image, bad magic, permissions, name in use...).
class IpcError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// For an image or panel this user may not open (or only read): the group to join. The packaged
// daemon (stepmodd@.service) runs as group 'stepmod' and makes its objects mode 0660.
inline constexpr const char* kGroupHint =
    "only the daemon's group may use it: `sudo usermod -aG stepmod $USER` (the packaged "
    "service's group), then log in again";

// Module names (docs/interface.md 2 `module.name`): 1..64 characters of a-z, 0-9, '-', '_'. Keeps
// the object inside /dev/shm (no '/') and the name usable in unit names and file names.
inline constexpr std::size_t kMaxNameLength = 64;
bool valid_name(std::string_view name) noexcept;
// Throws IpcError naming the rule when `name` is not valid.
void check_name(std::string_view name);

// shm_open() names: "/stepmod.<name>" and "/stepmod.<name>.sim".
std::string image_object(std::string_view name);
std::string panel_object(std::string_view name);

// A mapped shared-memory object. Move-only; unmaps on destruction, and unlinks the object too if
// this process created it.
class ShmMapping {
 public:
  ShmMapping() = default;
  ShmMapping(ShmMapping&& o) noexcept { *this = std::move(o); }
  ShmMapping& operator=(ShmMapping&& o) noexcept;
  ShmMapping(const ShmMapping&) = delete;
  ShmMapping& operator=(const ShmMapping&) = delete;
  ~ShmMapping() { reset(); }

  // Creates `object` (O_CREAT|O_EXCL, mode 0660 regardless of umask) of `size` zeroed bytes.
  // The creator holds an exclusive flock(2) on it until reset(): the kernel releases it when the
  // process ends, however it ends. If it exists already, holds `magic` with a non-zero owner pid
  // (u64 at `pid_offset`) and nobody holds its lock, it is a leftover of a crashed daemon (even
  // if that pid has since been reused): it is unlinked and created anew. In every other case (owner
  // alive, unknown content) it throws IpcError telling the user which file to remove; a live
  // daemon's image is never taken over.
  static ShmMapping create(const std::string& object, std::size_t size, std::string_view magic,
                           std::size_t pid_offset);
  // Opens an existing object of at least `min_size` bytes, read-write if possible, else read-only
  // (`writable()` tells). Throws IpcError if it is absent or too small.
  static ShmMapping open(const std::string& object, std::size_t min_size);

  void* data() const noexcept { return addr_; }
  std::size_t size() const noexcept { return size_; }
  bool writable() const noexcept { return writable_; }
  const std::string& object() const noexcept { return object_; }
  // create() only: the owner pid and the content of a stale leftover it replaced (pid 0 and
  // empty if there was none), so that the caller can tell what it replaced.
  std::uint64_t replaced_pid() const noexcept { return replaced_pid_; }
  const std::vector<std::uint8_t>& replaced_content() const noexcept { return replaced_; }
  // Unmaps (and unlinks, if created here) now.
  void reset() noexcept;

 private:
  void* addr_ = nullptr;
  std::size_t size_ = 0;
  std::string object_;
  bool owner_ = false;
  bool writable_ = false;
  std::uint64_t replaced_pid_ = 0;
  std::vector<std::uint8_t> replaced_;
  int lock_fd_ = -1;  // create(): the descriptor holding the owner's lock
};

// What a reader expects at the start of a stepmod object (stepmod_image_t, stepmod_panel_t: an
// 8-byte magic, published last by the creator, then the layout version), and how its errors name
// the object.
struct ObjectHeader {
  const char* magic;         // STEPMOD_IMAGE_MAGIC, STEPMOD_PANEL_MAGIC
  std::uint32_t version;     // the version this program understands
  const char* what;          // "a stepmod image": what an object with another magic is not
  const char* magic_hint;    // said after "bad magic" ("; daemon still starting?"), or ""
  const char* version_name;  // "layout": "has layout version N"
};

// Throws IpcError naming /dev/shm<object> when `magic_field` (read with acquire) or `version`
// is not what `expect` says.
void check_header(const std::string& object, const char* magic_field, std::uint32_t version,
                  const ObjectHeader& expect);

// Opens `object` into `map` (ShmMapping::open) and checks its header (check_header) before the
// caller trusts anything else in it; the mapping as a Header.
template <class Header>
Header* open_checked(ShmMapping& map, const std::string& object, std::size_t size,
                     const ObjectHeader& expect) {
  map = ShmMapping::open(object, size);
  auto* header = static_cast<Header*>(map.data());
  check_header(object, header->magic, header->version, expect);
  return header;
}

}  // namespace stepmod::ipc

#pragma once
// Server side of the shared-memory I/O image (INTERFACE.md section 3), owned by stepmodd's
// control thread: one output snapshot and one input publication per scan.
#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "core/module_shape.hpp"
#include "ipc/shm_object.hpp"
#include "ipc/stepmod_image.h"

namespace stepmod::ipc {

// A 3202 blend message (INTERFACE.md 3, offsets 192..415) waiting to be processed.
struct BlendMessage {
  std::uint32_t seq = 0;  // the request sequence to acknowledge with finish_message()
  std::array<std::int32_t, STEPMOD_MSG_DINTS> data{};
};

class ShmImage {
 public:
  // Attempts per read_outputs() before giving up on a PLC that is writing the whole time.
  static constexpr unsigned kReadTries = 64;

  // Creates /dev/shm/stepmod.<name> (mode 0660, 4096 bytes) and fills the header for `shape`.
  // Throws IpcError for a bad name or if the object exists and its owner is alive or unknown;
  // a leftover of a crashed daemon (owner pid gone) is replaced (see ShmMapping::create).
  ShmImage(const std::string& name, const ModuleShape& shape);
  ~ShmImage() = default;  // unmaps and unlinks
  ShmImage(const ShmImage&) = delete;
  ShmImage& operator=(const ShmImage&) = delete;

  const std::string& name() const noexcept { return name_; }
  const ModuleShape& shape() const noexcept { return shape_; }

  // One consistent snapshot of the PLC's output words, sign-extended to int32 (unused words 0).
  // false if the PLC was mid-write on every try: `out` is untouched and the caller keeps its
  // previous snapshot, as a real module keeps the last good backplane frame.
  bool read_outputs(ImageWords& out) const noexcept;

  // Writes the input words under the input seqlock (each truncated to the word size), then
  // increments the scan counter: one call per completed scan.
  void publish_inputs(const ImageWords& in) noexcept;

  // Daemon health (INTERFACE.md 3.3): the flags (STEPMOD_HEALTH_*) and the late-edge fault count
  // that the next publish_inputs() writes with the input words, under the same seqlock.
  void set_health(std::uint32_t flags, std::uint32_t late_faults) noexcept {
    health_flags_ = flags;
    late_faults_ = late_faults;
  }
  std::uint32_t health_flags() const noexcept;
  std::uint32_t late_faults() const noexcept;

  std::uint64_t scan_counter() const noexcept;
  // The PLC heartbeat value (INTERFACE.md 3.2); the caller watches it for changes.
  std::uint64_t heartbeat() const noexcept;

  // 3202 blend message: a request the module has not finished yet (request seq != done seq).
  std::optional<BlendMessage> pending_message() const noexcept;
  // Stores the result and marks request `seq` done.
  void finish_message(std::uint32_t seq, std::int32_t result) noexcept;

  // For tests and diagnostics.
  const stepmod_image_t& raw() const noexcept { return *img_; }

 private:
  std::string name_;
  ModuleShape shape_;
  ShmMapping map_;
  stepmod_image_t* img_ = nullptr;
  std::uint32_t health_flags_ = 0;
  std::uint32_t late_faults_ = 0;
};

}  // namespace stepmod::ipc

#pragma once
// Server side of the shared-memory I/O image (docs/interface.md section 3), owned by stepmodd's
// control thread: one output snapshot and one input publication per scan.
#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "core/module_shape.hpp"
#include "ipc/health.hpp"
#include "ipc/shm_object.hpp"
#include "ipc/stepmod_image.h"

namespace stepmod::ipc {

// A 3202 blend message (docs/interface.md 3, offsets 192..415) waiting to be processed.
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
  // The same, also giving the (even) sequence value the snapshot was taken under (the PLC
  // supervisor compares it across scans to see writes that bypass the seqlock).
  bool read_outputs(ImageWords& out, std::uint32_t& seq) const noexcept;
  // The output sequence now (odd: a PLC is writing, or died writing).
  std::uint32_t output_seq() const noexcept;

  // Writes the input words under the input seqlock (each truncated to the word size), then
  // increments the scan counter: one call per completed scan.
  void publish_inputs(const ImageWords& in) noexcept { publish_inputs(in, health_); }
  // The same with the daemon health words (docs/interface.md 3.3), under the same seqlock.
  void publish_inputs(const ImageWords& in, const Health& health) noexcept;

  // "stale image of stepmodd pid N (module 3601, scan counter ..., ...)" if creating the image
  // replaced a crashed daemon's leftover, else empty.
  std::string replaced_description() const;

  std::uint64_t scan_counter() const noexcept;
  // The PLC heartbeat value (docs/interface.md 3.2); the caller watches it for changes.
  std::uint64_t heartbeat() const noexcept;

  // 3202 blend message: a request the module has not finished yet (request seq != done seq).
  std::optional<BlendMessage> pending_message() const noexcept;
  // Stores the result and marks request `seq` done.
  void finish_message(std::uint32_t seq, std::int32_t result) noexcept;

  // Section 3.4: the error reason of `axis` (0-based, < 2), written under the input seqlock by the
  // next publish_inputs().
  void set_reason(unsigned axis, const stepmod_reason_t& reason) noexcept;

  // Section 3.6: what axis `axis` (0-based, < 2) holds beyond its words, written under the input
  // seqlock by the next publish_inputs().
  void set_unit_state(unsigned axis, const stepmod_unit_state_t& state) noexcept;

  // Section 3.5: the commissioning lease as its holder wrote it.
  struct Lease {
    std::uint32_t holder = 0;  // pid, 0 = free
    std::uint32_t seq = 0;
    std::int64_t expiry_ns = 0;  // CLOCK_MONOTONIC
  };
  Lease lease() const noexcept;
  // Frees the lease if `holder` still holds it (a compare-and-swap: a release or a new take in
  // between wins). Returns whether this call freed it.
  bool free_lease(std::uint32_t holder) noexcept;

  // For tests and diagnostics.
  const stepmod_image_t& raw() const noexcept { return *img_; }

 private:
  std::string name_;
  ModuleShape shape_;
  ShmMapping map_;
  stepmod_image_t* img_ = nullptr;
  Health health_;                              // as last published
  std::array<stepmod_reason_t, 2> reasons_{};  // written with the next publication
  std::array<stepmod_unit_state_t, 2> units_{};  // the same (section 3.6)
};

}  // namespace stepmod::ipc

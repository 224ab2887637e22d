#pragma once
// PLC side of the shared-memory I/O image (docs/interface.md section 3), for stepmodctl, tests and
// C++ soft PLCs. Any process; one Client per thread (it holds no locks, but write helpers are
// read-modify-write sequences under the output seqlock).
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>

#include "core/module_shape.hpp"
#include "ipc/health.hpp"
#include "ipc/shm_object.hpp"
#include "ipc/stepmod_image.h"

namespace stepmod::ipc {

class Client {
 public:
  static constexpr unsigned kReadTries = 100000;

  // Opens /dev/shm/stepmod.<name>. Throws IpcError if the name is invalid, the image is absent,
  // not a stepmod image, of another layout version, or has an impossible shape.
  explicit Client(const std::string& name);

  const std::string& name() const noexcept { return name_; }
  const ModuleShape& shape() const noexcept { return shape_; }
  ModuleType type() const noexcept { return shape_.type; }
  // False when the image could only be opened read-only (permissions): writes throw IpcError.
  bool writable() const noexcept { return map_.writable(); }

  // Consistent snapshots (words sign-extended; unused words 0); false if a writer kept the
  // sequence busy for kReadTries attempts.
  bool read_inputs(ImageWords& in) const noexcept;
  bool read_outputs(ImageWords& out) const noexcept;
  // The daemon health words (docs/interface.md 3.3), consistent with one input publication.
  Health read_health() const noexcept;
  // The error reason of axis/channel `axis` (0-based; docs/interface.md 3.4), consistent with one
  // input publication; seq 0 and an empty text when none (or no consistent read).
  stepmod_reason_t read_reason(unsigned axis) const noexcept;
  // What axis/channel `axis` holds beyond its words (docs/interface.md 3.6), consistent with one
  // input publication; nullopt for no such axis or no consistent read.
  std::optional<stepmod_unit_state_t> read_unit_state(unsigned axis) const noexcept;

  // Writes the first output_words words under the output seqlock (truncated to the word size).
  void write_outputs(const ImageWords& out);
  // Sets one output word, leaving the others as they are.
  void write_word(unsigned index, std::int32_t value);
  // Read-modify-write of the whole output image as one seqlock write: `edit` sees the present
  // words and changes them; no other cooperating writer can interleave.
  void update_outputs(const std::function<void(ImageWords&)>& edit);

  std::uint64_t scan_counter() const noexcept;
  // Waits until the scan counter has advanced by `n` from its value at the call. false on
  // timeout (module not scanning).
  bool wait_scans(std::uint64_t n, std::chrono::milliseconds timeout) const;
  // Waits until the scan counter reaches `target`.
  bool wait_scan_counter(std::uint64_t target, std::chrono::milliseconds timeout) const;

  // PLC heartbeat (docs/interface.md 3.2): +1; a PLC calls it every scan while in Run mode.
  void heartbeat();
  std::uint64_t heartbeat_value() const noexcept;

  // 3202 blend message (docs/interface.md 3, offsets 192..415): writes the 52 DINTs, increments the
  // request sequence and waits for the module to mark it done. Returns the module's result
  // (0 accepted), or nullopt on timeout.
  std::optional<std::int32_t> send_message(std::span<const std::int32_t> data,
                                           std::chrono::milliseconds timeout);

  const stepmod_image_t& raw() const noexcept { return *img_; }
  // The image itself, for the commissioning lease (ipc/lease.hpp): its
  // fields are atomics shared with the daemon. Throws IpcError when the image is read-only.
  stepmod_image_t& writable_image();

 private:
  void require_writable() const;

  std::string name_;
  ShmMapping map_;
  stepmod_image_t* img_ = nullptr;
  ModuleShape shape_{};
};

}  // namespace stepmod::ipc

#pragma once
// What a PLC program needs of the module's I/O image, whoever carries it: the shared memory of a
// running stepmodd (plc/shm_port.hpp) or the virtual-time test machine
// (tests/support/virtual_port.hpp). The dialects (module_types/m3601/plc_3601.hpp, ...) sequence
// their commands through this interface only, so stepmodctl and the tests run the same PLC code.
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "core/module_shape.hpp"

namespace stepmod::plc {

// The last error reason of one axis/channel (docs/interface.md 3.4, docs/error-reasons.md).
struct ReasonView {
  std::uint32_t seq = 0;   // +1 per recorded reason
  std::uint32_t code = 0;  // item code: module * 10000 + list * 100 + number
  std::string text;        // "3601-CE-05: Vp 500 is below Vs 1000"
  unsigned list() const noexcept { return code / 100u % 100u; }
};

class Port {
 public:
  virtual ~Port() = default;

  // The module type the image belongs to (the image header's, for shared memory).
  virtual ModuleType type() const = 0;

  // The output words as they are now.
  virtual ImageWords outputs() const = 0;
  // Writes every output word as one consistent write (the module never sees half of it).
  virtual void write_outputs(const ImageWords& out) = 0;
  // Read-modify-write of the output words, as one consistent write.
  virtual void update_outputs(const std::function<void(ImageWords&)>& edit) = 0;
  // A consistent snapshot of the input words; false if none could be taken.
  virtual bool read_inputs(ImageWords& in) const = 0;

  // Waits until `n` more module scans have completed. With n >= 2 at least one whole scan ran
  // after the call, so it saw everything written before. false: the module did not scan in time.
  virtual bool wait_scans(unsigned n) = 0;
  // Lets `d` pass while the PLC keeps running (heartbeat), e.g. to hold a level-held bit.
  virtual void pass(std::chrono::nanoseconds d) = 0;
  // Waits until `done` holds for the input words, at most `limit`; returns whether it held.
  virtual bool wait_inputs(const std::function<bool(const ImageWords&)>& done,
                           std::chrono::nanoseconds limit) = 0;
  // The last error reason of axis/channel `unit` (0-based); nullopt where the image carries
  // none (the virtual test machine): the error bits alone then decide.
  virtual std::optional<ReasonView> reason(unsigned unit) const {
    (void)unit;
    return std::nullopt;
  }
};

}  // namespace stepmod::plc

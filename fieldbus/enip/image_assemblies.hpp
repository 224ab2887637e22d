#pragma once
// The assembly instances' data over the shared-memory image (docs/interface.md §3): instance 100
// is the module's input words, 150 its output words, each word little-endian as CIP carries it
// (INT for the 3601/3602, DINT for the 3202). A write of 150 is one consistent PLC write (one
// seqlock write of the whole output image) and a PLC heartbeat (§3.1, §3.2), as the Modbus
// server's writes are.
#include <array>
#include <cstdint>
#include <span>

#include "fieldbus/enip/message_router.hpp"
#include "ipc/stepmod_image.h"

namespace stepmod::enip {

class ImageAssemblies : public AssemblyData {
 public:
  // `image` must stay valid, with a valid header (word size 2 or 4, at most 16 words).
  explicit ImageAssemblies(stepmod_image_t& image) noexcept : img_(image) {}

  AssemblyLayout layout() const noexcept;
  // A read that keeps meeting a write in progress returns the last consistent words (the I/O
  // thread never waits on the module).
  void read(std::uint32_t instance, std::span<std::uint8_t> out) noexcept override;
  void write_output(std::span<const std::uint8_t> bytes) noexcept override;
  // A Run packet whose data was written already: the PLC's heartbeat alone.
  void beat() noexcept;

 private:
  stepmod_image_t& img_;
  std::array<std::int32_t, STEPMOD_MAX_WORDS> last_input_{};
  std::array<std::int32_t, STEPMOD_MAX_WORDS> last_output_{};
};

}  // namespace stepmod::enip

#pragma once
// What the control thread asks of an emulated module. One implementation per module type
// (module/m3601/, later 3602 and 3202); each does exactly what its manual says.
#include <array>
#include <cstdint>
#include <memory>
#include <span>

#include "gpio/backend.hpp"
#include "planner/motion_port.hpp"
#include "rt/clock.hpp"

namespace stepmod::module {

enum class ModuleType : std::uint32_t { k3601 = 3601, k3602 = 3602, k3202 = 3202 };

// The backplane words of one image, sign-extended to 32 bits (16-bit modules use the low 16 bits
// of each value; ipc/ truncates and sign-extends at the shared-memory boundary).
struct ImageWords {
  std::array<std::int32_t, 16> w{};
  bool operator==(const ImageWords&) const = default;
};

// Static facts of a module type (INTERFACE.md section 3 header fields).
struct ModuleShape {
  ModuleType type;
  unsigned axes;
  unsigned word_bytes;    // 2 or 4
  unsigned output_words;  // PLC -> module
  unsigned input_words;   // module -> PLC
};
ModuleShape shape_of(ModuleType t) noexcept;

// What a personality may touch besides the image: one MotionPort per axis and the inputs.
struct AxisIo {
  planner::MotionPort* motion = nullptr;
};

class Personality {
 public:
  virtual ~Personality() = default;

  virtual const ModuleShape& shape() const noexcept = 0;

  // An input edge (electrical level, own timestamp), delivered in time order as soon as the
  // control thread sees it, between scans.
  virtual void on_input(const gpio::InputEvent& e) = 0;

  // One I/O scan: `plc_out` is a consistent snapshot of the PLC's output words; the personality
  // writes the whole input image into `plc_in`.
  virtual void scan(const ImageWords& plc_out, ImageWords& plc_in, Nanos now) = 0;

  // The PLC left Run mode (heartbeat timeout, INTERFACE.md 3.2): every move stops and the
  // position becomes invalid, as the manuals say of a PLC switched to Program mode.
  virtual void plc_stopped(Nanos now) = 0;

  // Shutdown: immediate stop of every axis.
  virtual void shutdown() = 0;
};

// Creates the personality for `type`. `backend` gives input levels and the pulse format;
// `axes` has one MotionPort per axis of the module.
std::unique_ptr<Personality> make_personality(ModuleType type, gpio::Backend& backend,
                                              std::span<planner::MotionPort* const> axes);

}  // namespace stepmod::module

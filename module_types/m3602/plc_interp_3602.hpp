#pragma once
// The 3602's interpolated moves as a PLC program writes them (3602 manual ch. 3, tables 9.4,
// 9.23-9.26): the block in all sixteen output words, the data first with the command bits clear
// and the bits set >= 10 ms later (the manual: the backplane moves the image in 8-word blocks, so
// words 8..15 may still be stale when the bits arrive together with them), held, released. Hold and
// Resume of a path are axis 1's Hold and Resume (interpolation bits 0 in the Resume). Kept apart
// from plc_3602 (single-axis commands), which it uses for the edge-triggered axis-1 commands.
#include <chrono>
#include <cstdint>

#include "core/module_shape.hpp"
#include "module_types/m3602/plc_3602.hpp"
#include "plc/move_profile.hpp"
#include "plc/port.hpp"

namespace stepmod::plc {

// One interpolated move in the manual's terms.
struct PathMove3602 {
  enum class Method : std::uint8_t {
    kLinear,
    kViaPoint,  // the circle through the start, `point` and `end`
    kCentreCw,  // centre `point`; end = start: a full circle
    kCentreCcw,
    kRadiusCw,  // signed `radius`: > 0 the shorter arc, < 0 the longer one
    kRadiusCcw,
  };
  Method method = Method::kLinear;
  bool absolute = false;  // points are positions (else offsets from the start point)
  std::int32_t end_x = 0;
  std::int32_t end_y = 0;
  std::int32_t point_x = 0;  // via point or centre
  std::int32_t point_y = 0;
  std::int32_t radius = 0;
  Profile profile;  // vector speed (steps/s), accel / decel (steps/ms/s), type
};

namespace m3602 {
// Command LSW bits 9..14 of a move (3602 manual table 9.4).
std::uint16_t interpolation_bits(const PathMove3602& m);
// The block into all sixteen words (axis 2's command words 8 / 9 = 0, the method's unused words
// 0). `command_bits`: with LSW bits 9..14 (else the data alone); `gpo`: axis 1's GPO bit kept.
void put_interpolated(ImageWords& w, const PathMove3602& m, bool command_bits, std::uint16_t gpo);
}  // namespace m3602

class Interp3602 {
 public:
  // `settle`: how long the data stand before the bits are set (the manual: >= 10 ms).
  explicit Interp3602(Port& port,
                      std::chrono::milliseconds timeout = std::chrono::milliseconds(2000),
                      Sequencing seq = {},
                      std::chrono::milliseconds settle = std::chrono::milliseconds(10));

  // Starts the move (errors on axis 1: Command Error, Invalid Profile).
  Outcome move(const PathMove3602& m);
  // Hold on axis 1: the path stops along it.
  Outcome hold();
  // Resume on axis 1 with a new vector profile (A39: the Resume block's words 4..7).
  Outcome resume(const Profile& p);
  // Immediate Stop on axis 1: both axes stop (3602-PI-07).
  Outcome immediate_stop();
  // Waits until the path has ended: both axes stopped (Axis Stopped on both).
  Outcome wait_done(std::chrono::nanoseconds timeout);

 private:
  Outcome finish(bool timed_out, const char* what);

  Port& port_;
  Plc3602 axes_;
  std::chrono::milliseconds timeout_;
  Sequencing seq_;
  std::chrono::milliseconds settle_;
};

}  // namespace stepmod::plc

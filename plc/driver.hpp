#pragma once
// What every dialect's PLC driver (module_types/mXXXX/plc_XXXX.hpp) holds and does alike: the port
// of its module type, how long it waits and how many scans each step takes, whether THIS command
// was refused (plc/verdict.hpp), and the answer read back: the input image and the error bits of
// one unit's status word, named by the manual's status table. Each driver derives from Driver and
// writes only how its commands are put into its words.
#include <chrono>
#include <cstdint>
#include <string>

#include "core/module_shape.hpp"
#include "plc/bit_names.hpp"
#include "plc/command_answer.hpp"
#include "plc/move_profile.hpp"
#include "plc/port.hpp"
#include "plc/verdict.hpp"

namespace stepmod::plc {

// How many module scans each step of a command waits. Any count >= 2 is correct (a whole scan
// then saw the write); the test fixtures pin the counts their timing assertions were written for.
struct Sequencing {
  unsigned hold_scans = 2;     // a command's words stay this long before its bit is released
  unsigned release_scans = 2;  // and this long after
  unsigned config_scans = 2;   // in configuration mode, then again back in command mode
  // A command bit left at 1 (by an earlier PLC program or an interrupted stepmodctl) would hide
  // the next 0->1 edge: release it first. Tests that set bits on purpose turn this off.
  bool release_stale_bits = true;
};

// `Type`: the module type the port must have. `StatusBits`: the field table of the status word
// that holds the error bits (3601/3602 status MSW, 3202 status DINT); `StatusWord(in, unit)`: that
// word of unit `unit` (axis or channel, 0-based) in the input image.
template <ModuleType Type, const auto& StatusBits,
          std::uint32_t (*StatusWord)(const ImageWords& in, unsigned unit)>
class Driver {
 public:
  // `timeout` bounds each handshake wait and is named in timeout messages. Throws
  // std::invalid_argument if the port's module is not of type `Type`.
  explicit Driver(Port& port, std::chrono::milliseconds timeout = std::chrono::milliseconds(2000),
                  Sequencing seq = {})
      : port_(port_of_type(port, Type)),
        timeout_(timeout),
        seq_(seq),
        verdict_(port, shape_of(Type).axes) {}

  Port& port() noexcept { return port_; }

 protected:
  static constexpr ErrorBitSet kErrorBits = error_bits_of(StatusBits);
  // Errors that mean "the module rejected or failed this command".
  static constexpr std::uint32_t kCommandErrors = command_errors(kErrorBits);

  // The module's answer to a command of `unit`: the input image, and whether the `error_mask`
  // bits of its status word say the command was refused (or that it timed out).
  Outcome finish(unsigned unit, std::uint32_t error_mask, bool timed_out, const std::string& what) {
    Outcome o;
    if (!read_answer(port_, timed_out, what, timeout_, o)) return o;
    const std::uint32_t errors = StatusWord(o.in, unit) & error_mask;
    verdict_.judge(o, unit, errors, set_bit_names(errors, StatusBits),
                   lists_of(error_mask, kErrorBits), what, stale_);
    return o;
  }

  // Waits until `idle(input image)` holds for `unit`, then answers as finish() without errors.
  template <typename Idle>
  Outcome wait_until(unsigned unit, const Idle& idle, std::chrono::nanoseconds timeout,
                     const std::string& what) {
    const bool done = port_.wait_inputs([&](const ImageWords& in) { return idle(in); }, timeout);
    return finish(unit, 0, !done, what);
  }

  Port& port_;
  std::chrono::milliseconds timeout_;
  Sequencing seq_;
  Verdict verdict_;                // was THIS command refused (plc/verdict.hpp)
  Stale stale_ = Stale::kRefused;  // what an earlier error bit means for the running command
};

}  // namespace stepmod::plc

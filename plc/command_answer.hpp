#pragma once
// What every dialect's PLC side does with the module's answer to a command: the error bits of its
// status word, looked up by name in the manual's status table (the three manuals name them
// alike), and the message of a command the module did not answer in time.
#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/bit_table.hpp"
#include "plc/port.hpp"
#include "plc/move_profile.hpp"
#include "plc/verdict.hpp"

namespace stepmod::plc {

// The error bits of a status word whose field table is `t` (3601/3602 status MSW, 3202 status).
template <typename Table>
consteval ErrorBitSet error_bits_of(const Table& t) {
  // Direct calls, no helper lambda: clang (clang-tidy) refuses a consteval lambda's call with a
  // captured parameter as "not a constant expression"; the body of a consteval function is not.
  using W = std::uint32_t;
  return {mask_of<W>(t, "Configuration Error"), mask_of<W>(t, "Command Error"),
          mask_of<W>(t, "Invalid Profile"),     mask_of<W>(t, "Input Error"),
          mask_of<W>(t, "Home Invalid"),        mask_of<W>(t, "Position Invalid")};
}

// Errors that mean "the module rejected or failed this command".
constexpr std::uint32_t command_errors(const ErrorBitSet& b) noexcept {
  return b.ce | b.ip;
}

// `port`, when its module is of type `t`; else std::invalid_argument naming both (each dialect's
// PLC driver takes its port through this).
inline Port& port_of_type(Port& port, ModuleType t) {
  if (port.type() != t) {
    throw std::invalid_argument("the module is a " +
                                std::to_string(static_cast<unsigned>(port.type())) + ", not a " +
                                std::to_string(static_cast<unsigned>(t)));
  }
  return port;
}

// Reads the module's answer into `o`; false (with `o` saying so) when the command timed out
// waiting for it.
inline bool read_answer(const Port& port, bool timed_out, std::string_view what,
                        std::chrono::milliseconds timeout, Outcome& o) {
  port.read_inputs(o.in);
  if (!timed_out) return true;
  o.ok = false;
  o.timed_out = true;
  o.message = std::string(what) + ": no answer from the module within " +
              std::to_string(timeout.count()) + " ms (is stepmodd running?)";
  return false;
}

}  // namespace stepmod::plc

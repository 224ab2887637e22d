#pragma once
// Counts events of one kind and lets a log line about them through at most once per period: a
// client that connects in a loop cannot flood the journal (the Modbus server, the EtherNet/IP
// adapter).
#include <cstdint>

#include "core/clock.hpp"

namespace stepmod::ipc {

class LogThrottle {
 public:
  explicit LogThrottle(Nanos period) noexcept : period_(period) {}

  // Counts one event; true when a line is due, with `since` = the events since the last line
  // (this one included).
  bool count(Nanos now, std::uint64_t& since) noexcept {
    ++quiet_;
    if (last_ != 0 && now - last_ < period_) return false;
    since = quiet_;
    last_ = now;
    quiet_ = 0;
    return true;
  }

 private:
  Nanos period_;
  Nanos last_ = 0;
  std::uint64_t quiet_ = 0;
};

}  // namespace stepmod::ipc

#include "ipc/modbus_connection.hpp"

#include <algorithm>
#include <tuple>

namespace stepmod::ipc {

ModbusTimeout next_timeout(const ModbusConnection& c, Nanos idle_timeout) noexcept {
  if (c.closing_since != 0) {
    return {c.closing_since + kModbusCloseTimeout, "answers before a malformed frame not taken",
            false};
  }
  ModbusTimeout t{c.last_heard + idle_timeout, "idle", true};
  if (c.frame_start != 0 && c.frame_start + kModbusFrameTimeout < t.at) {
    t = {c.frame_start + kModbusFrameTimeout, "frame incomplete", false};
  }
  return t;
}

std::list<ModbusConnection>::iterator eviction_choice(std::list<ModbusConnection>& clients) {
  // Lower ranks go first: closing (0), never served (1), served (2); then the oldest last_heard.
  const auto rank = [](const ModbusConnection& c) {
    const int kind = c.closing_since != 0 ? 0 : (c.served ? 2 : 1);
    return std::make_tuple(kind, c.last_heard);
  };
  return std::min_element(
      clients.begin(), clients.end(),
      [&](const ModbusConnection& a, const ModbusConnection& b) { return rank(a) < rank(b); });
}

}  // namespace stepmod::ipc

// Recording why an error bit is set (AxisState::note, docs/error-reasons.md). Control thread
// only; no allocation (the text is formatted into the reason's fixed buffer).
#include <algorithm>
#include <cstdio>
#include <cstring>

#include "module/axis/axis_state.hpp"

namespace stepmod::module::axis {

namespace {
struct LatchBit {
  bool Latches::*bit;
  ErrorList list;
};
constexpr LatchBit kErrorBits[] = {
    {&Latches::configuration_error, ErrorList::kConfiguration},
    {&Latches::command_error, ErrorList::kCommand},
    {&Latches::invalid_profile, ErrorList::kInvalidProfile},
    {&Latches::input_error, ErrorList::kInput},
    {&Latches::home_invalid, ErrorList::kHomeInvalid},
    {&Latches::position_invalid, ErrorList::kPositionInvalid},
};
}  // namespace

void AxisState::record(ErrorList list, unsigned number, const char* text) noexcept {
  const ModuleType t = rules.type;
  char id[24];
  format_item_id(id, sizeof id, t, list, number);
  char full[sizeof id + 2 + kReasonTextSize];
  std::snprintf(full, sizeof full, "%s: %s", id, text);
  // Cut to the image's 56 bytes (with the NUL): the log and the image show the same text.
  const std::size_t n = std::min(std::strlen(full), reason.text.size() - 1);
  std::memcpy(reason.text.data(), full, n);
  reason.text[n] = '\0';
  reason.code = item_code(t, list, number);
  ++reason.seq;
  noted_since_ = true;
}

void AxisState::vnote(const Item& item, const char* fmt, va_list args) noexcept {
  char text[kReasonTextSize];
  if (fmt == nullptr) {
    std::snprintf(text, sizeof text, "%s", item.what);
  } else {
    std::vsnprintf(text, sizeof text, fmt, args);
  }
  record(item.list, item.number(rules.type), text);
}

void AxisState::note(const Item& item, const char* fmt, ...) noexcept {
  va_list args;
  va_start(args, fmt);
  vnote(item, fmt, args);
  va_end(args);
}

void AxisState::reject(const Item& item, const char* fmt, ...) noexcept {
  fire(AxisEvent::kCommandRefused);
  va_list args;
  va_start(args, fmt);
  vnote(item, fmt, args);
  va_end(args);
}

void AxisState::reject_profile(const Item& item, const char* fmt, ...) noexcept {
  fire(AxisEvent::kProfileRefused);
  va_list args;
  va_start(args, fmt);
  vnote(item, fmt, args);
  va_end(args);
}

void AxisState::explain_new_errors() noexcept {
  if (!noted_since_) {
    for (const LatchBit& b : kErrorBits) {
      if (latches().*(b.bit) && !(explained_.*(b.bit))) {
        // The first new bit names the list; no item is known.
        record(b.list, 0, list_bit_name(b.list));
        break;
      }
    }
  }
  explained_ = latches();
  noted_since_ = false;
}

}  // namespace stepmod::module::axis

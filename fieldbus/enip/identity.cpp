#include "fieldbus/enip/identity.hpp"

#include <cstdio>

namespace stepmod::enip {

namespace {
void put_revision(Writer& w, const IdentityValues& id) noexcept {
  w.u8(id.major);
  w.u8(id.minor);
}
}  // namespace

IdentityValues identity_for(std::uint32_t module_type, std::uint32_t serial) noexcept {
  IdentityValues id;
  id.product_code = static_cast<std::uint16_t>(module_type);
  id.serial = serial;
  const int n = std::snprintf(id.name.data(), id.name.size(), "stepmod %u",
                              static_cast<unsigned>(module_type));
  id.name_length = static_cast<std::uint8_t>(n < 0 ? 0 : n);
  return id;
}

std::uint32_t identity_serial(std::string_view machine_id, std::string_view module_name) noexcept {
  std::uint32_t h = 2166136261u;
  const auto mix = [&h](std::string_view s) {
    for (const char c : s) {
      h ^= static_cast<std::uint8_t>(c);
      h *= 16777619u;
    }
  };
  mix(machine_id);
  mix(std::string_view("\0", 1));  // "ab"+"c" and "a"+"bc" differ
  mix(module_name);
  return h == 0 ? 1 : h;
}

std::uint16_t identity_status_word(bool owned, unsigned connections, bool any_run) noexcept {
  std::uint16_t s = owned ? identity_status::kOwned : 0;
  if (connections == 0) return s | identity_status::kNoIoConnection;
  return s | (any_run ? identity_status::kIoInRun : identity_status::kIoAllIdle);
}

void put_identity_all(Writer& w, const IdentityValues& id) noexcept {
  w.u16(id.vendor);
  w.u16(id.device_type);
  w.u16(id.product_code);
  put_revision(w, id);
  w.u16(id.status);
  w.u32(id.serial);
  w.short_string(id.product_name());
}

bool put_identity_attribute(Writer& w, const IdentityValues& id, std::uint8_t attribute) noexcept {
  switch (attribute) {
    case 1:
      w.u16(id.vendor);
      return true;
    case 2:
      w.u16(id.device_type);
      return true;
    case 3:
      w.u16(id.product_code);
      return true;
    case 4:
      put_revision(w, id);
      return true;
    case 5:
      w.u16(id.status);
      return true;
    case 6:
      w.u32(id.serial);
      return true;
    case 7:
      w.short_string(id.product_name());
      return true;
    case 8:
      w.u8(id.state);
      return true;
    default:
      return false;
  }
}

void put_identity_item_tail(Writer& w, const IdentityValues& id) noexcept {
  put_identity_all(w, id);
  w.u8(id.state);
}

}  // namespace stepmod::enip
